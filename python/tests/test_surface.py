"""sfit.Surface: evaluation equals the C++ evaluation, grid equals pointwise, saving/loading."""

import json
import pickle
import subprocess

import numpy as np
import pytest

import sfit
from conftest import CLOSED, OPEN, assert_same_surface, example, wavy_grid


def cxx_evaluate(helper, path, u, v):
    """S, S_u, S_v at (u_k, v_k) by the C++ library (eval_helper.cpp), each (n, 3)."""
    text = "".join(f"{a!r} {b!r}\n" for a, b in zip(u, v))
    r = subprocess.run([helper, str(path)], input=text, capture_output=True, text=True, timeout=60)
    assert r.returncode == 0, r.stderr
    values = np.array([[float(x) for x in line.split()] for line in r.stdout.splitlines()])
    return values[:, 0:3], values[:, 3:6], values[:, 6:9]


def sample_parameters(surface, n=400, seed=7):
    rng = np.random.default_rng(seed)
    # Inside the domain, on its ends, and outside it (clamped, or wrapped if periodic).
    u = np.concatenate([rng.uniform(0, surface.u_end, n), [0, surface.u_end, -0.5, surface.u_end + 0.7]])
    v = np.concatenate([rng.uniform(0, surface.v_end, n), [surface.v_end, 0, surface.v_end + 0.3, -1.2]])
    return u, v


@pytest.mark.parametrize("name,closed", sorted({**OPEN, **CLOSED}.items()))
def test_evaluation_equals_the_cxx_evaluation(eval_helper, tmp_path, name, closed):
    surface = sfit.fit(sfit.load_rows(example(name)), closed=closed).surface
    path = tmp_path / "s.json"
    surface.save(str(path))
    u, v = sample_parameters(surface)
    p, su, sv = cxx_evaluate(eval_helper, path, u, v)
    assert np.array_equal(surface(u, v), p)
    assert np.array_equal(surface.derivative(u, v, 1, 0), su)
    assert np.array_equal(surface.derivative(u, v, 0, 1), sv)


def test_evaluation_equals_scipy_bspline_tensor_product():
    interpolate = pytest.importorskip("scipy.interpolate", reason="scipy absent: independent check skipped")
    surface = sfit.fit(wavy_grid(), tol=0.01, degree_u=3, degree_v=2).surface
    cp = surface.control_points
    u = np.linspace(0, surface.u_end, 37)
    v = np.linspace(0, surface.v_end, 23)
    # S(u, v) = sum_i B_i(u) (sum_j B_j(v) P_ij): a curve in u whose coefficients are curves in v.
    bv = interpolate.BSpline(surface.knots_v, cp.transpose(1, 0, 2), surface.degree_v)
    inner = bv(v)  # (len(v), nu, 3)
    bu = interpolate.BSpline(surface.knots_u, inner.transpose(1, 0, 2), surface.degree_u)
    expected = bu(u)  # (len(u), len(v), 3)
    assert np.allclose(surface(u, v, grid=True), expected, rtol=0, atol=1e-12 * np.abs(cp).max())


@pytest.mark.parametrize("closed", ["", "u"])
def test_grid_equals_pointwise(closed):
    name = "d150_wing" if closed else "ship_px121_stations"
    surface = sfit.fit(sfit.load_rows(example(name)), closed=closed).surface
    u = np.linspace(-0.2, surface.u_end + 0.2, 41)
    v = np.linspace(0, surface.v_end, 17)
    U, V = np.meshgrid(u, v, indexing="ij")
    for f, kw in [(surface, {}), (surface.normal, {}), (surface.derivative, {"du": 1, "dv": 1}),
                  (surface.derivative, {"du": 0, "dv": 2})]:
        g = f(u, v, grid=True, **kw)
        assert g.shape == (41, 17, 3)
        assert np.array_equal(g.reshape(-1, 3), f(U.ravel(), V.ravel(), **kw))


def test_shapes_scalars_and_broadcasting(ship_rows):
    s = sfit.fit(ship_rows).surface
    assert s(0.5, 0.25).shape == (3,)
    assert np.array_equal(s(0.5, 0.25), s([0.5], [0.25])[0])
    v = np.linspace(0, s.v_end, 5)
    assert np.array_equal(s(0.5, v), s(np.full(5, 0.5), v))
    assert s([], []).shape == (0, 3)
    assert s(0.5, v, grid=True).shape == (1, 5, 3)


def test_derivatives_and_normals(ship_rows):
    s = sfit.fit(ship_rows).surface
    u, v, h = 1.3, 2.1, 1e-6
    su = s.derivative(u, v, 1, 0)
    fd = (s(u + h, v) - s(u - h, v)) / (2 * h)
    assert np.allclose(su, fd, rtol=1e-6, atol=1e-6)
    assert np.array_equal(s.derivative(u, v, 0, 0), s.derivative(u, v, du=0, dv=0))
    n = s.normal([u, 0.4], [v, 3.3])
    assert np.allclose(np.linalg.norm(n, axis=1), 1)
    assert abs(n[0] @ su) < 1e-12 * np.linalg.norm(su)
    assert abs(n[0] @ s.derivative(u, v, 0, 1)) < 1e-9


def test_evaluation_is_independent_of_threads(ship_rows):
    s = sfit.fit(ship_rows).surface
    u = np.linspace(0, s.u_end, 300_001)
    v = np.linspace(0, s.v_end, 300_001)
    assert np.array_equal(s(u, v, threads=1), s(u, v, threads=2))
    assert np.array_equal(s(u, v, threads=1), s(u, v))


def test_properties_are_the_json_contract(ship_rows, tmp_path):
    s = sfit.fit(ship_rows).surface
    j = s.to_json()
    assert j["type"] == "bspline_surface"
    assert_same_surface(s, j)
    nu, nv = s.count
    assert s.control_points.shape == (nu, nv, 3)
    assert len(s.knots_u) == nu + s.degree_u + 1
    assert s.u_end == s.knots_u[-1] and s.v_end == s.knots_v[-1]


def test_save_and_load_surface_round_trip(tmp_path):
    s = sfit.fit(sfit.load_rows(example("d150_wing")), closed="u").surface
    s.save(str(tmp_path / "wing.json"))
    t = sfit.load_surface(str(tmp_path / "wing.json"))
    assert_same_surface(t, s.to_json())
    assert t.periodic == (True, False)
    u, v = sample_parameters(s, 50)
    assert np.array_equal(s(u, v), t(u, v))


def test_pickle_round_trip(ship_rows):
    s = sfit.fit(ship_rows).surface
    t = pickle.loads(pickle.dumps(s))
    assert np.array_equal(t.control_points, s.control_points) and t.degree == s.degree


def test_save_writes_every_format_of_the_cli(cli, tmp_path, ship_rows):
    from conftest import run_cli

    formats = sfit.output_formats()
    assert "json" in formats
    fit = sfit.fit(ship_rows)
    fit.save(str(tmp_path / "fit.json"))
    for ext in formats:
        mine = tmp_path / f"py.{ext}"
        fit.surface.save(str(mine))
        assert mine.stat().st_size > 0, ext
        theirs = tmp_path / f"cli.{ext}"
        code, err = run_cli(cli, "convert", tmp_path / "fit.json", "-q", "-o", theirs)
        assert code == 0, err
        if ext in ("json", "obj", "stl", "ply", "vts", "vtk"):
            assert mine.read_bytes() == theirs.read_bytes(), ext  # same writer, same bytes
