"""sfit.fit(): the CLI's surface bit for bit, the report, the tolerance at every point."""

import json

import numpy as np
import pytest

import sfit
from conftest import CLOSED, OPEN, assert_same_surface, cli_fit, deviations, example, wavy_grid


@pytest.mark.parametrize("name,closed", sorted({**OPEN, **CLOSED}.items()))
def test_default_fit_equals_the_cli_bit_for_bit(cli, tmp_path, name, closed):
    args = ["--closed", closed] if closed else []
    j = cli_fit(cli, tmp_path, example(name), *args)
    fit = sfit.fit(sfit.load_rows(example(name)), closed=closed)
    assert_same_surface(fit.surface, j)
    report = fit.report
    assert set(report) == set(j["report"])  # exactly the JSON report's keys
    for key in report:
        if key != "seconds":
            assert report[key] == j["report"][key], key
    assert report["within_tolerance"] is True
    # Closed in u: periodic, or clamped with its first and last columns equal (corner knots on
    # closed rows put a crease at the seam, docs/method.md 7.13).
    cp = np.asarray(fit.surface.control_points)
    assert (fit.surface.periodic[0] or np.array_equal(cp[0], cp[-1])) == (closed == "u")
    assert fit.surface.periodic[1] is False


@pytest.mark.parametrize(
    "kwargs,args",
    [
        ({"tol": 0.05, "degree_u": 2, "degree_v": 4}, ["--tol", "0.05", "--degree-u", "2", "--degree-v", "4"]),
        ({"tol": (0.1, 0.02, 0.03)}, ["--tol", "0.1,0.02,0.03"]),
        ({"tol_rel": 1e-4, "parameters": "chord"}, ["--tol-rel", "1e-4", "--parameters", "chord"]),
        ({"search": "linear", "degree": 2}, ["--search", "linear", "--degree", "2"]),
        ({"tol": 0}, ["--tol", "0"]),
    ],
)
def test_options_equal_the_cli_options(cli, tmp_path, kwargs, args):
    j = cli_fit(cli, tmp_path, example("ship_px121_stations"), *args)
    fit = sfit.fit(sfit.load_rows(example("ship_px121_stations")), **kwargs)
    assert_same_surface(fit.surface, j)
    assert fit.report["tolerance"] == j["report"]["tolerance"]


def test_closed_ragged_blade_with_options_equals_the_cli(cli, tmp_path):
    j = cli_fit(cli, tmp_path, example("iea3p4mw_blade_ragged9"), "--closed", "u", "--tol", "0.001",
                "--parameters", "centripetal")
    fit = sfit.fit(sfit.load_rows(example("iea3p4mw_blade_ragged9")), closed="u", tol=0.001,
                   parameters="centripetal")
    assert_same_surface(fit.surface, j)


def test_default_tolerance_is_the_clis_fraction_of_the_diagonal(ship_rows):
    points = np.concatenate(ship_rows)
    diagonal = np.linalg.norm(points.max(axis=0) - points.min(axis=0))
    t = sfit.fit(ship_rows).report["tolerance"]
    assert t == pytest.approx([1e-3 * diagonal] * 3, rel=1e-15)
    assert sfit.fit(ship_rows, tol_rel=None, tol=None).report["tolerance"] == t


@pytest.mark.parametrize("name,closed", sorted({**OPEN, **CLOSED}.items()))
def test_every_point_within_tolerance(name, closed):
    fit = sfit.fit(sfit.load_rows(example(name)), closed=closed, tol_rel=1e-4)
    dev = np.abs(deviations(fit))
    t = np.array(fit.report["tolerance"])
    assert (dev <= t).all()
    assert np.allclose(dev.max(axis=0), fit.report["max_deviation"], rtol=1e-9, atol=1e-12)


def test_interpolates_at_zero_tolerance(ship_rows):
    fit = sfit.fit(ship_rows, tol=0)
    assert fit.report["within_tolerance"] and fit.report["roundoff"] > 0
    assert np.abs(deviations(fit)).max() <= 2 * fit.report["roundoff"]


def test_grid_array_equals_list_of_rows():
    grid = wavy_grid()
    a = sfit.fit(grid, tol=0.01)
    b = sfit.fit([row for row in grid], tol=0.01)
    assert np.array_equal(a.surface.control_points, b.surface.control_points)
    assert np.array_equal(a.u, b.u) and np.array_equal(a.v, b.v)
    assert a.u.shape == (30 * 40,) and a.v.shape == (30,)
    assert a.row_sizes == [40] * 30


def test_closed_both_directions_is_periodic_both_ways():
    s = np.linspace(0, 2 * np.pi, 24, endpoint=False)
    t = np.linspace(0, 2 * np.pi, 12, endpoint=False)
    S, T = np.meshgrid(s, t)
    torus = np.stack([(3 + np.cos(S)) * np.cos(T), (3 + np.cos(S)) * np.sin(T), np.sin(S)], -1)
    fit = sfit.fit(torus, closed="uv", tol=0.01)
    assert fit.surface.periodic == (True, True)
    nu, nv = fit.surface.count
    assert fit.surface.control_points.shape == (nu + 3, nv + 3, 3)
    assert (np.abs(deviations(fit)) <= 0.01).all()


def test_fit_save_json_holds_the_report(tmp_path, ship_rows):
    fit = sfit.fit(ship_rows)
    fit.save(str(tmp_path / "hull.json"))
    j = json.loads((tmp_path / "hull.json").read_text())
    assert_same_surface(fit.surface, j)
    assert j["report"]["row_counts"] == fit.report["row_counts"]


def test_tolerance_by_position_equals_by_keyword(ship_rows):
    a = sfit.fit(ship_rows, 0.05)
    b = sfit.fit(ship_rows, tol=0.05)
    assert np.array_equal(a.surface.control_points, b.surface.control_points)


def test_the_stub_names_every_public_name():
    import ast
    import pathlib

    stub = pathlib.Path(sfit.__file__).with_suffix(".pyi")
    tree = ast.parse(stub.read_text())
    names = {n.name for n in tree.body if isinstance(n, (ast.ClassDef, ast.FunctionDef))}
    names |= {t.id for n in tree.body if isinstance(n, ast.AnnAssign) for t in [n.target]}
    assert set(sfit.__all__) <= names
    # Every keyword option of sfit.fit (the binding's table) is in its docstring.
    for key in ("tol", "tol_rel", "degree_u", "closed", "search", "parameters", "threads"):
        assert f"    {key}: " in sfit.fit.__doc__
