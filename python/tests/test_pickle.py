"""Fit and Surface pickle, copy and deep-copy round trips, bit for bit; bad states refused."""

import copy
import pickle

import numpy as np
import pytest

import sfit
from conftest import example, wavy_grid


def same_surface(a, b):
    assert a.to_json() == b.to_json()
    assert np.array_equal(a.control_points, b.control_points)
    u = np.linspace(-0.1, a.u_end + 0.1, 31)
    v = np.linspace(0, a.v_end, 17)
    assert np.array_equal(a(u, v, grid=True), b(u, v, grid=True))


@pytest.fixture(scope="module")
def fits():
    weighted = [np.column_stack([r, np.linspace(0.5, 3.0, len(r))]) for r in wavy_grid(12, 15)]
    return [sfit.fit(wavy_grid(), tol=0.01),
            sfit.fit(sfit.load_rows(example("d150_wing")), closed="u"),
            sfit.fit(weighted, tol=0.02)]


@pytest.mark.parametrize("how", ["pickle", "copy", "deepcopy"])
def test_surface_round_trips(fits, how):
    for f in fits:
        s = f.surface
        t = {"pickle": lambda x: pickle.loads(pickle.dumps(x, protocol=pickle.HIGHEST_PROTOCOL)),
             "copy": copy.copy, "deepcopy": copy.deepcopy}[how](s)
        assert t is not s and isinstance(t, sfit.Surface)
        same_surface(s, t)


@pytest.mark.parametrize("how", ["pickle", "copy", "deepcopy"])
def test_fit_round_trips(fits, tmp_path, how):
    for k, f in enumerate(fits):
        g = {"pickle": lambda x: pickle.loads(pickle.dumps(x)), "copy": copy.copy,
             "deepcopy": copy.deepcopy}[how](f)
        assert g is not f and isinstance(g, sfit.Fit)
        same_surface(f.surface, g.surface)
        assert g.report == f.report
        for name in ("u", "v", "points"):
            assert np.array_equal(getattr(g, name), getattr(f, name))
        assert g.row_sizes == f.row_sizes
        # The whole state, weights included, is the same.
        assert g.__reduce__()[1] == f.__reduce__()[1]
        # And what it writes: the .json carries surface and report.
        f.save(str(tmp_path / f"a{k}.json"))
        g.save(str(tmp_path / f"b{k}.json"))
        assert (tmp_path / f"a{k}.json").read_bytes() == (tmp_path / f"b{k}.json").read_bytes()


def test_weights_travel_with_a_pickled_fit(fits):
    state = fits[2].__reduce__()[1][0]
    assert len(state[7]) == 8 * len(fits[2].points)  # one float64 weight per point
    assert fits[0].__reduce__()[1][0][7] == b""


def test_surface_setstate_of_garbage_raises_and_changes_nothing(fits):
    s = copy.deepcopy(fits[0].surface)
    before = s.to_json()
    with pytest.raises(sfit.Error) as e:
        s.__setstate__("garbage")
    assert e.value.code == "input-syntax" and "pickle" in str(e.value)
    with pytest.raises(sfit.Error) as e:
        s.__setstate__(42)
    assert e.value.code == "input-data" and "Surface state" in str(e.value)
    with pytest.raises(sfit.Error) as e:
        s.__setstate__('{"type": "bspline_surface", "degree": [3, 3]}')
    assert e.value.code == "input-data"
    assert s.to_json() == before
    # A good state replaces the surface.
    other = fits[1].surface
    s.__setstate__(other.__getstate__())
    same_surface(s, other)


def test_fit_state_of_garbage_raises():
    with pytest.raises(sfit.Error):
        sfit._sfit._fit_from_state((2, "", "", b"", b"", b"", [], b""))
    with pytest.raises(sfit.Error):
        sfit._sfit._fit_from_state(("x",))


def clipped_scan_lines():
    """Scan lines across the unit disc, points at random along each (rows of very different
    extents): the data the parameters 'geometric' are for."""
    rng = np.random.default_rng(11)
    rows = []
    for y in np.linspace(-0.98, 0.98, 30):
        h = np.sqrt(1 - y * y)
        n = max(6, int(60 * h))
        x = np.sort(rng.uniform(-h, h, n))
        rows.append(np.column_stack([x, np.full(n, y), 0.3 * np.sin(3 * x) * np.cos(2 * y) + 0.1 * x * y]))
    return rows


@pytest.mark.parametrize("how", ["pickle", "copy", "deepcopy"])
def test_points_own_v_travels_with_a_fit(how):
    f = sfit.fit(clipped_scan_lines(), parameters="geometric")
    assert f.report["parameters"] == "geometric"
    assert f.v_points.shape == (len(f.points),) and len(f.v) == len(f.row_sizes)
    g = {"pickle": lambda x: pickle.loads(pickle.dumps(x)), "copy": copy.copy,
         "deepcopy": copy.deepcopy}[how](f)
    assert np.array_equal(g.v_points, f.v_points) and np.array_equal(g.u, f.u)
    assert g.__reduce__()[1] == f.__reduce__()[1]
    # Every point within T at its own (u, v), on the copy's surface.
    d = np.abs(g.surface(g.u, g.v_points) - g.points)
    assert (d <= np.asarray(f.report["tolerance"]) * (1 + 1e-9)).all()
    # The row rules leave it empty.
    assert sfit.fit(clipped_scan_lines(), parameters="chord").v_points.shape == (0,)


def test_a_version_1_fit_state_still_reads(fits):
    state = fits[0].__reduce__()[1][0]
    assert state[0] == 2 and len(state) == 9
    old = sfit._sfit._fit_from_state((1,) + tuple(state[1:8]))
    assert np.array_equal(old.u, fits[0].u) and old.v_points.shape == (0,)


def box_stations():
    """Hull-like stations with a sharp chine and a sharp deck corner (generated)."""
    rows = []
    for t in np.linspace(0, 1, 20):
        b, d = 5 + 1.5 * np.sin(t * np.pi), 3 + 0.6 * t
        l0, l1, l2 = 0.6 * b, 0.8 * d, 0.4 * b
        x = np.linspace(0, 1, 120) * (l0 + l1 + l2)
        y = np.where(x < l0, x, np.where(x < l0 + l1, l0 + 0.1 * (x - l0), l0 + 0.1 * l1 - (x - l0 - l1)))
        z = np.where(x < l0, 0.05 * x * x / l0, np.where(x < l0 + l1, 0.05 * l0 + (x - l0), 0.05 * l0 + l1))
        rows.append(np.column_stack([np.full(len(x), 30 * t), y, z]))
    return rows


def test_adaptive_knots_fit_holds_and_travels():
    uni = sfit.fit(box_stations(), knots="uniform")
    f = sfit.fit(box_stations(), knots="adaptive")
    nu, nv = f.report["control_points"]
    assert nu * nv < 0.7 * np.prod(uni.report["control_points"])
    assert f.surface.uniform_knots == (False, False) or f.surface.uniform_knots[0] is False
    g = pickle.loads(pickle.dumps(f))
    assert np.array_equal(g.surface.knots_u, f.surface.knots_u)
    d = np.abs(g.surface(g.u, g.v[np.repeat(np.arange(len(g.row_sizes)), g.row_sizes)]) - g.points)
    assert (d <= np.asarray(f.report["tolerance"]) * (1 + 1e-9)).all()
