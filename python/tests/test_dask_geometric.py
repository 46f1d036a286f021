"""sfit.dask.fit(parameters="geometric") on a LocalCluster equals the in-memory geometric fit
(each point's (u, v) from a base plane, corrected by projection; scattered least squares with
a smoothness term): scan lines clipped by a circle, so rows cover different parts of the
domain and the row rules would not do."""

import numpy as np
import pytest

import sfit
import sfit.dask

import dask.array as da  # python3-dask, python3-distributed: scripts/deps
import distributed

N_POINTS = 200_000


def clipped_field(n_points, seed=5):
    """A smooth field sampled on about 0.9 sqrt(n) scan lines clipped by the unit circle (each
    row as many points as its chord is long, slightly wavy in x and y). (n, 4): x, y, z, row."""
    m = int(np.sqrt(n_points) * 0.9)
    y = np.linspace(-0.98, 0.98, m) + 0.003 * np.sin(7 * np.arange(m))
    half = np.sqrt(1 - y ** 2)
    sizes = np.maximum(4, np.round(half / half.sum() * n_points).astype(int))
    sizes[m // 2] += n_points - sizes.sum()
    out = []
    for j in range(m):
        s = np.linspace(-half[j], half[j], sizes[j])
        x = s + 0.01 * np.sin(9 * s + j)
        yj = y[j] + 0.02 * np.sin(3 * x)
        z = 0.3 * np.sin(2 * x + 0.5) * np.cos(1.5 * yj) + 0.1 * x * yj
        out.append(np.column_stack([x, yj, z, np.full(sizes[j], j)]))
    return np.concatenate(out)


def as_rows(points):
    cut = np.flatnonzero(np.diff(points[:, 3])) + 1
    return [r[:, :3] for r in np.split(points, cut)]


def relative_difference(a, b):
    return float(np.max(np.abs(a - b)) / np.max(np.abs(b)))


def uneven_chunks(n, chunks):
    """Chunks of unequal sizes, cutting rows anywhere."""
    rng = np.random.default_rng(chunks)
    cuts = np.sort(rng.choice(np.arange(1, n), size=chunks - 1, replace=False))
    return tuple(np.diff(np.concatenate([[0], cuts, [n]])).tolist())


@pytest.fixture(scope="module")
def data():
    return clipped_field(N_POINTS)


@pytest.fixture(scope="module")
def tol(data):
    box = data[:, :3].max(axis=0) - data[:, :3].min(axis=0)
    return [1e-3 * float(np.linalg.norm(box))] * 3


def in_memory(data, counts, tol):
    mem = sfit.dask.in_memory_fit(as_rows(data), counts, tol=tol, parameters="geometric")
    assert mem.report["parameters"] == "geometric"
    return mem


def test_the_rows_cover_different_parts_of_the_domain(data):
    rows = as_rows(data)
    widths = [r[:, 0].max() - r[:, 0].min() for r in rows]
    assert min(widths) < 0.5 * max(widths)


@pytest.mark.parametrize("chunks", [4, 16, 64])
def test_any_chunking_equals_the_in_memory_geometric_fit(cluster, data, tol, chunks):
    counts = (12, 12)  # held at the rule's default smoothing weight, base parameters
    mem = in_memory(data, counts, tol)
    with distributed.Client(cluster):
        x = da.from_array(data, chunks=(uneven_chunks(len(data), chunks), 4)).persist()
        got = sfit.dask.fit(x, tol=tol, parameters="geometric", counts=counts)
    r = got.report
    assert r["chunks"] == chunks and r["parametrization"] == "geometric"
    assert r["within_tolerance"] and r["smoothing"] == 1e-4 and r["corrections"] == 0
    assert relative_difference(got.surface.control_points, mem.surface.control_points) < 1e-10
    assert np.array_equal(got.surface.knots_u, mem.surface.knots_u)
    assert np.array_equal(got.surface.knots_v, mem.surface.knots_v)
    # Every point within T, evaluated here on the distributed surface at the in-memory
    # fit's parameters (one (u, v) per point), and the same worst deviation as its check.
    dev = np.abs(got.surface(mem.u, mem.v_points) - data[:, :3]).max(axis=0)
    assert np.all(dev <= np.array(tol))
    np.testing.assert_allclose(dev, r["max_deviation"], rtol=1e-9)
    np.testing.assert_allclose(mem.report["max_deviation"], r["max_deviation"], rtol=1e-9)


def test_the_lowered_smoothing_weight_and_corrections_as_in_memory(cluster, data, tol):
    """At 8 x 8 the default weight leaves the surface far from the data in a corner without
    data; the library lowers it to 1e-8, and so does the distributed rule. The empty spans are
    then held by a weak term: round-off in the order of the sums (chunks against the
    library's blocks of points) grows there to about 1e-10 of the control points; on the
    data the two surfaces agree to 1e-10 of T (measured: 3e-11)."""
    counts = (8, 8)
    mem = in_memory(data, counts, tol)
    with distributed.Client(cluster):
        x = da.from_array(data, chunks=(uneven_chunks(len(data), 16), 4)).persist()
        got = sfit.dask.fit(x, tol=tol, parameters="geometric", counts=counts)
    r = got.report
    assert [p["guard"] for p in got.pairs] == ["far from the data", None]
    assert r["within_tolerance"] and r["smoothing"] == 1e-8
    assert relative_difference(got.surface.control_points, mem.surface.control_points) < 1e-9
    on_data = got.surface(mem.u, mem.v_points) - mem.surface(mem.u, mem.v_points)
    assert np.abs(on_data).max() < 1e-10 * tol[0]
    np.testing.assert_allclose(mem.report["max_deviation"], r["max_deviation"], rtol=1e-9)


def test_the_count_search_holds_t_at_every_point(cluster, data, tol):
    with distributed.Client(cluster):
        x = da.from_array(data, chunks=(uneven_chunks(len(data), 16), 4)).persist()
        got = sfit.dask.fit(x, tol=tol, parameters="geometric")
    r = got.report
    nu, nv = r["control_points"]
    assert r["within_tolerance"] and all(d <= t for d, t in zip(r["max_deviation"], tol))
    held = {tuple(p["counts"]) for p in got.pairs if p["holds"]}
    assert (nu, nv) in held and (nu - 1, nv) not in held and (nu, nv - 1) not in held
    # Not more control points than the in-memory search's (it corrects on a sample).
    mem = sfit.fit(as_rows(data), tol=tol, parameters="geometric")
    assert nu * nv <= np.prod(mem.report["control_points"])
    assert got.v is None and got.report["partial_bytes"] == 8 * nu * nv * (49 + 3)


def test_closed_rows_and_bad_options_are_sfit_errors(cluster, data):
    with distributed.Client(cluster):
        x = da.from_array(data[:5000], chunks=(1000, 4))
        with pytest.raises(sfit.Error, match="open rows") as e:
            sfit.dask.fit(x, parameters="geometric", closed="u")
        assert e.value.code == "usage"
        with pytest.raises(sfit.Error, match="256 MiB"):
            sfit.dask.fit(x, parameters="geometric", counts=(1500, 1500))
