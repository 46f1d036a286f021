"""Grid layout, derivatives, normals, curvature, closest points, from_knots, STEP/IGES
surfaces read back, read-only arrays; paths with NUL, the thread limit and weights."""

import subprocess

import numpy as np
import pytest

import sfit
from conftest import assert_same_surface, cli_fit, example, wavy_grid

interpolate = pytest.importorskip("scipy.interpolate", reason="SciPy is the independent reference")


@pytest.fixture(scope="module")
def open_surface():
    return sfit.fit(wavy_grid(), tol=0.01, degree_u=3, degree_v=2).surface


@pytest.fixture(scope="module")
def closed_surface():
    return sfit.fit(sfit.load_rows(example("d150_wing")), closed="u").surface


def reference(s, u, v, du=0, dv=0, grid=True):
    """S (or a partial derivative) by SciPy: B_u(u) P B_v(v)^T from BSpline.design_matrix
    (values) or BSpline.derivative (derivatives)."""
    cp = s.control_points
    if du == 0 and dv == 0:
        Bu = interpolate.BSpline.design_matrix(u, s.knots_u, s.degree_u).toarray()
        Bv = interpolate.BSpline.design_matrix(v, s.knots_v, s.degree_v).toarray()
        if grid:
            return np.einsum("ia,abk,jb->ijk", Bu, cp, Bv)
        return np.einsum("na,abk,nb->nk", Bu, cp, Bv)
    bv = interpolate.BSpline(s.knots_v, cp.transpose(1, 0, 2), s.degree_v)
    if dv:
        bv = bv.derivative(dv)
    inner = bv(v)  # (len(v), nu_full, 3)
    bu = interpolate.BSpline(s.knots_u, inner.transpose(1, 0, 2), s.degree_u)
    if du:
        bu = bu.derivative(du)
    full = bu(u)  # (len(u), len(v), 3)
    return full if grid else full[np.arange(len(u)), np.arange(len(v))]


def test_grid_layout_first_axis_is_u():
    # An (M, N, 3) grid: M rows (v) of N points (u). Interpolated, it comes back at its own
    # parameters as (N, M, 3): [i, j] is S(u_i, v_j), the point i of row j.
    g = wavy_grid(6, 9)
    f = sfit.fit(g, tol=0)
    s = f.surface
    u = f.u[:9]  # u of the points of row 0 (a grid: the same in every row)
    back = s(u, f.v, grid=True)
    assert back.shape == (9, 6, 3)
    assert np.allclose(back, g.transpose(1, 0, 2), atol=1e-9)
    assert np.array_equal(back[2, 4], s(u[2], f.v[4]))


@pytest.mark.parametrize("which", ["open", "closed"])
def test_values_equal_scipy_design_matrices(open_surface, closed_surface, which):
    s = open_surface if which == "open" else closed_surface
    u = np.linspace(0, s.u_end, 29)
    v = np.linspace(0, s.v_end, 13)
    scale = np.abs(s.control_points).max()
    assert np.allclose(s(u, v, grid=True), reference(s, u, v), rtol=0, atol=1e-12 * scale)
    rng = np.random.default_rng(2)
    up, vp = rng.uniform(0, s.u_end, 300), rng.uniform(0, s.v_end, 300)
    assert np.allclose(s(up, vp), reference(s, up, vp, grid=False), rtol=0, atol=1e-12 * scale)


@pytest.mark.parametrize("du,dv", [(1, 0), (0, 1), (2, 0), (1, 1), (0, 2)])
def test_derivatives_equal_scipy_and_finite_differences(open_surface, closed_surface, du, dv):
    for s in (open_surface, closed_surface):
        scale = np.abs(s.control_points).max()
        u = np.linspace(0.05, s.u_end - 0.05, 23)
        v = np.linspace(0.05, s.v_end - 0.05, 11)
        d = s.derivative(u, v, du, dv, grid=True)
        assert np.allclose(d, reference(s, u, v, du, dv), rtol=0, atol=1e-10 * scale)
        # Central differences of the order below.
        h = 1e-5
        lower = (du - 1, dv) if du else (du, dv - 1)
        shift = (h, 0) if du else (0, h)
        f = (lambda a, b: s(a, b, grid=True)) if lower == (0, 0) else (
            lambda a, b: s.derivative(a, b, *lower, grid=True))
        fd = (f(u + shift[0], v + shift[1]) - f(u - shift[0], v - shift[1])) / (2 * h)
        assert np.allclose(d, fd, rtol=0, atol=1e-6 * scale * max(1, np.abs(d).max() / scale))


def test_derivatives_in_one_pass_equal_the_single_ones(closed_surface):
    s = closed_surface
    rng = np.random.default_rng(4)
    u, v = rng.uniform(-1, s.u_end + 1, 500), rng.uniform(0, s.v_end, 500)
    d = s.derivatives(u, v, order=2)
    assert d.shape == (500, 6, 3)
    assert np.array_equal(d[:, 0], s(u, v))
    for k, (a, b) in enumerate([(1, 0), (0, 1), (2, 0), (1, 1), (0, 2)], start=1):
        assert np.array_equal(d[:, k], s.derivative(u, v, a, b))
    g = s.derivatives(u[:7], v[:5], order=1, grid=True)
    assert g.shape == (7, 5, 3, 3)
    assert s.derivatives(0.3, 0.2).shape == (3, 3)
    n = s.normal(u, v)
    assert np.allclose(np.linalg.norm(n, axis=1), 1)
    assert np.allclose(np.einsum("nk,nk->n", n, d[:, 1]), 0, atol=1e-9 * np.abs(d[:, 1]).max())
    with pytest.raises(sfit.Error):
        s.derivatives(u, v, order=3)


def patch(kind, R=2.0, n=25):
    """Rows on a sphere (kind "sphere") or a cylinder of radius R: u along a row."""
    a = np.linspace(-0.6, 0.6, n)
    b = np.linspace(-0.5, 0.5, n - 4)
    A, B = np.meshgrid(a, b)  # (rows, points)
    if kind == "sphere":
        pts = np.stack([R * np.cos(B) * np.cos(A), R * np.cos(B) * np.sin(A), R * np.sin(B)], -1)
    else:
        pts = np.stack([R * np.cos(A), R * np.sin(A), B * R], -1)
    return sfit.fit(pts, tol=1e-7 * R)


@pytest.mark.parametrize("kind", ["sphere", "cylinder"])
def test_curvature_of_a_sphere_and_a_cylinder(kind):
    R = 2.0
    f = patch(kind, R)
    s = f.surface
    u = np.linspace(0.2, 0.8, 7) * s.u_end
    v = np.linspace(0.2, 0.8, 5) * s.v_end
    c = s.curvature(u, v, grid=True)
    assert c.gaussian.shape == (7, 5)
    # The orientation of S_u x S_v against the outward direction decides the signs.
    p, n = s(u, v, grid=True), s.normal(u, v, grid=True)
    axis = p if kind == "sphere" else p * [1, 1, 0]
    outward = np.sign(np.einsum("ijk,ijk->ij", n, axis))
    assert np.all(np.abs(outward) == 1)
    if kind == "sphere":
        assert np.allclose(c.gaussian, 1 / R**2, rtol=1e-3)
        assert np.allclose(c.mean * outward, -1 / R, rtol=1e-3)
        assert np.allclose(c.k1, c.k2, atol=1e-3 / R)
    else:
        assert np.allclose(c.gaussian, 0, atol=1e-3 / R**2)
        assert np.allclose(c.mean * outward, -1 / (2 * R), rtol=1e-3)
        assert np.allclose(np.where(outward > 0, c.k1, -c.k2), 0, atol=1e-3 / R)
    one = s.curvature(u[1], v[2])
    assert isinstance(one.gaussian, float) and one.gaussian == c.gaussian[1, 2]
    assert one.mean == pytest.approx((one.k1 + one.k2) / 2)


def test_closest_point_of_offset_points_and_beyond_the_edges():
    s = patch("sphere").surface
    rng = np.random.default_rng(8)
    u0, v0 = rng.uniform(0.1, 0.9, 40) * s.u_end, rng.uniform(0.1, 0.9, 40) * s.v_end
    off = rng.uniform(-0.5, 0.5, 40)
    p = s(u0, v0) + off[:, None] * s.normal(u0, v0)
    u, v = s.closest_point(p)
    assert np.allclose(u, u0, atol=1e-8) and np.allclose(v, v0, atol=1e-8)
    assert s.closest_point(p[3]) == (u[3], v[3])
    # A plane from its knots: points beyond an edge or a corner land on it.
    ku = np.array([0, 0, 1, 2, 2.0])
    kv = np.array([0, 0, 1, 1.0])
    cp = np.array([[[x, y, 0.0] for y in (0, 1)] for x in (0, 1, 2)])
    plane = sfit.Surface.from_knots(ku, kv, cp, 1, 1)
    u, v = plane.closest_point(np.array([[-3, 0.5, 1], [1.5, 9, -2], [5, -5, 0], [0.7, 0.2, 4]]))
    assert np.allclose(u, [0, 1.5, 2, 0.7], atol=1e-12)
    assert np.allclose(v, [0.5, 1, 0, 0.2], atol=1e-12)


def test_from_knots_round_trips_and_refuses_other_knots(open_surface, closed_surface):
    for s in (open_surface, closed_surface):
        t = sfit.Surface.from_knots(s.knots_u, s.knots_v, s.control_points, s.degree_u, s.degree_v,
                                    *s.periodic)
        assert t.to_json() == s.to_json()
    s = open_surface
    bad = s.knots_u.copy()
    bad[s.degree_u + 1] = bad[s.degree_u + 3] + 0.5  # decreasing
    with pytest.raises(sfit.Error) as e:
        sfit.Surface.from_knots(bad, s.knots_v, s.control_points, s.degree_u, s.degree_v)
    assert "knots_u" in str(e.value)
    with pytest.raises(sfit.Error):
        sfit.Surface.from_knots(s.knots_u, s.knots_v, s.control_points[:, :, :2], 3, 2)


def non_uniform(s):
    """`s` with its inner u knots moved (one made a corner: degree-fold) and its v knots
    squeezed toward 0: a non-uniform surface of the same control points."""
    ku = s.knots_u.copy()
    p = s.degree_u
    if s.periodic[0]:
        n = len(ku) - 2 * p - 1
        ku = ku + 0.4 * np.sin(2 * np.pi * (ku - ku[p]) / n)  # periodic spacing kept
    else:
        inner = ku[p + 1:len(ku) - p - 1]
        ku[p + 1:len(ku) - p - 1] = inner ** 1.3 / inner[-1] ** 0.3
        ku[p + 2:2 * p + 1] = ku[p + 1]  # a p-fold knot
    kv = s.knots_v.copy()
    if not s.periodic[1]:
        kv = kv ** 1.5
    return sfit.Surface.from_knots(ku, kv, s.control_points, s.degree_u, s.degree_v, *s.periodic)


def test_non_uniform_knots_evaluate_round_trip_and_pickle(open_surface, closed_surface, tmp_path):
    import pickle
    for k, s in enumerate((open_surface, closed_surface)):
        t = non_uniform(s)
        assert t.uniform_knots[0] is False
        assert t.to_json()["version"] == 2
        u = np.linspace(0, t.u_end, 37)
        v = np.linspace(0, t.v_end, 23)
        assert np.allclose(t(u, v, grid=True), reference(t, u, v), rtol=0, atol=1e-12 * np.abs(t.control_points).max())
        back = pickle.loads(pickle.dumps(t))
        assert np.array_equal(back.knots_u, t.knots_u) and np.array_equal(back.knots_v, t.knots_v)
        assert np.array_equal(back(u, v, grid=True), t(u, v, grid=True))
        path = str(tmp_path / f"nu{k}.json")
        t.save(path)
        r = sfit.load_surface(path)
        assert np.array_equal(r.knots_u, t.knots_u) and np.array_equal(r(u, v, grid=True), t(u, v, grid=True))
        for ext in ("step", "iges"):
            if ext not in sfit.output_formats():
                continue
            path = str(tmp_path / f"nu{k}.{ext}")
            t.save(path)
            r = sfit.load_surface(path)
            assert np.allclose(r.knots_u, t.knots_u, rtol=0, atol=1e-12 * t.u_end)
            assert np.allclose(r(u, v, grid=True), t(u, v, grid=True), rtol=0, atol=1e-9 * np.abs(t.control_points).max())


@pytest.mark.parametrize("ext", ["step", "iges"])
def test_load_surface_reads_back_step_and_iges(open_surface, closed_surface, tmp_path, ext):
    if ext not in sfit.output_formats():
        pytest.skip(f"this build has no {ext} (OpenCASCADE absent)")
    for k, s in enumerate([open_surface, closed_surface]):
        path = str(tmp_path / f"s{k}.{ext}")
        s.save(path)
        t = sfit.load_surface(path)
        assert t.degree == s.degree and t.periodic == s.periodic and t.count == s.count
        assert np.array_equal(t.knots_u, s.knots_u) and np.array_equal(t.knots_v, s.knots_v)
        if ext == "iges":  # written with 17 significant digits: the same doubles
            assert np.array_equal(t.control_points, s.control_points)
        else:  # OpenCASCADE's STEP writer keeps 13 significant digits
            scale = np.abs(s.control_points).max()
            assert np.allclose(t.control_points, s.control_points, rtol=0, atol=1e-12 * scale)
    (tmp_path / "x.step").write_text("not a step file")
    with pytest.raises(sfit.Error) as e:
        sfit.load_surface(str(tmp_path / "x.step"))
    assert e.value.code == "input-syntax"


def test_arrays_whose_writes_would_be_lost_are_read_only(closed_surface):
    f = sfit.fit(wavy_grid(), tol=0.05)
    c = sfit.fit_curve(wavy_grid()[0], tol=0.01)
    for a in [closed_surface.control_points, closed_surface.knots_u, closed_surface.knots_v,
              f.u, f.v, f.points, c.curve.knots, c.curve.control_points, c.parameters,
              c.max_deviation]:
        assert not a.flags.writeable
        with pytest.raises(ValueError):
            a[0] = 1
    assert closed_surface(0.1, 0.2).flags.writeable  # results are the caller's


def test_paths_with_nul_are_refused(closed_surface, tmp_path):
    f = sfit.fit(wavy_grid(), tol=0.05)
    for call in [lambda p: sfit.load_rows(p), lambda p: sfit.load_surface(p),
                 lambda p: closed_surface.save(p), lambda p: f.save(p)]:
        with pytest.raises(sfit.Error) as e:
            call(str(tmp_path / "a.json") + "\0.rows")
        assert e.value.code == "usage" and "NUL" in str(e.value)
    assert not list(tmp_path.iterdir())


def test_thread_counts_above_the_library_limit_are_refused(closed_surface):
    for call in [lambda: sfit.fit(wavy_grid(), threads=10**6),
                 lambda: closed_surface(0.1, 0.1, threads=10**6),
                 lambda: closed_surface.closest_point([0, 0, 0], threads=10**6)]:
        with pytest.raises(sfit.Error) as e:
            call()
        assert e.value.code == "usage" and "256" in str(e.value) and e.value.option == "threads"


def test_load_rows_returns_the_weights_and_fits_as_the_cli(cli, tmp_path):
    g = wavy_grid(8, 12)
    w = np.linspace(0.2, 5.0, g.shape[0] * g.shape[1]).reshape(g.shape[:2])
    path = tmp_path / "w.rows"
    with open(path, "w") as out:
        for row, wr in zip(g, w):
            for p, q in zip(row, wr):
                out.write(f"{p[0]!r} {p[1]!r} {p[2]!r} {q!r}\n")
            out.write("\n")
    rows = sfit.load_rows(str(path))
    assert [r.shape for r in rows] == [(12, 4)] * 8
    assert np.array_equal(np.stack(rows)[:, :, 3], w)
    j = cli_fit(cli, tmp_path, path, "--tol", "0.02")
    weighted = sfit.fit(rows, tol=0.02).surface
    assert_same_surface(weighted, j)
    # The weights matter: without them the surface is another one.
    plain = sfit.fit([r[:, :3] for r in rows], tol=0.02).surface
    assert not np.array_equal(plain.control_points, weighted.control_points)
    with pytest.raises(sfit.Error):
        sfit.fit([rows[0], rows[1][:, :3]] + rows[2:], tol=0.02)
