"""Shared fixtures of the Python tests: data sets of examples/, the CLI and the C++ helper.

CTest (python/CMakeLists.txt) sets PYTHONPATH to the build's python folder, SFIT_CLI and
SFIT_EVAL_HELPER. Run by hand:
    PYTHONPATH=build/python SFIT_CLI=build/apps/sfit/sfit \
    SFIT_EVAL_HELPER=build/python/sfit_python_eval_helper /usr/bin/python3 -m pytest python/tests
"""

import json
import os
import pathlib
import subprocess

import numpy as np
import pytest

import sfit

REPO = pathlib.Path(__file__).resolve().parents[2]
EXAMPLES = REPO / "examples"
BAD_INPUT = REPO / "tests" / "bad_input"

# The shared data sets of examples/ and how `sfit fit` is told their topology.
OPEN = {"ship_px121_stations": "", "table1_synthetic": ""}
CLOSED = {"d150_wing": "u", "iea3p4mw_blade_ragged9": "u"}


def example(name):
    return str(EXAMPLES / (name + ".rows"))


def program(variable):
    path = os.environ.get(variable)
    if not path or not os.path.exists(path):
        pytest.skip(f"{variable} is not set to a built program (CTest sets it); skipped")
    return path


@pytest.fixture(scope="session")
def cli():
    return program("SFIT_CLI")


@pytest.fixture(scope="session")
def eval_helper():
    return program("SFIT_EVAL_HELPER")


def run_cli(cli, *args):
    """Runs `sfit ARGS`; returns (exit code, stderr)."""
    r = subprocess.run([cli, *map(str, args)], capture_output=True, text=True, timeout=300)
    return r.returncode, r.stderr


def cli_fit(cli, tmp_path, rows_path, *args):
    """`sfit fit ROWS ARGS -o out.json`: the surface and report dicts of the CLI."""
    out = tmp_path / "cli.json"
    code, err = run_cli(cli, "fit", rows_path, "-q", "-o", out, *args)
    assert code == 0, err
    return json.loads(out.read_text())


def assert_same_surface(surface, j):
    """The module's surface equals the JSON contract form `j` bit for bit."""
    assert list(surface.degree) == j["degree"]
    assert list(surface.periodic) == j["periodic"]
    assert np.array_equal(surface.knots_u, np.array(j["knots_u"]))
    assert np.array_equal(surface.knots_v, np.array(j["knots_v"]))
    cp = np.array(j["control_points"], dtype=float)
    assert surface.control_points.shape == cp.shape
    assert np.array_equal(surface.control_points, cp)


def deviations(fit):
    """S(u_j, v_j) - D_j of every point, (P, 3): v of the point's row, or of the point itself
    where the surface has one per point (parameters 'geometric')."""
    v = fit.v_points if len(fit.v_points) else np.repeat(fit.v, fit.row_sizes)
    return fit.surface(fit.u, v) - fit.points


@pytest.fixture
def ship_rows():
    return sfit.load_rows(example("ship_px121_stations"))


def wavy_grid(m=30, n=40):
    """An (m, n, 3) height grid z = f(x, y) with x along a row."""
    x = np.linspace(0.0, 10.0, n)
    y = np.linspace(0.0, 6.0, m)
    X, Y = np.meshgrid(x, y)
    Z = np.sin(X) * np.cos(0.7 * Y) + 0.1 * X
    return np.stack([X, Y, Z], axis=-1)


@pytest.fixture(scope="module")
def cluster():
    """A LocalCluster of 2 worker processes, one thread each, for the sfit.dask tests
    (distributed imported here, so the other tests need not)."""
    import distributed
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as c:
        yield c
