"""LAS files in sfit.dask: the points as stored (scale and offset applied), the scan lines as
rows across the pieces a large file is read in, the fit equal to the in-memory one, and the
faults named."""

import struct

import numpy as np
import pytest

import sfit
import sfit.dask
from sfit import _las

import distributed


def scan(lines=23, seed=4):
    """Scan lines of an oscillating mirror over a smooth field, 30 ... 90 points each, every
    other line run backwards: a list of (n, 3) arrays in metres (UTM-like offsets)."""
    rng = np.random.default_rng(seed)
    rows = []
    for j in range(lines):
        n = int(rng.integers(30, 91))
        s = np.linspace(0, 1, n)
        x = 200 * (s + 0.03 * np.sin(2 * np.pi * s))  # a mirror's uneven sweep
        x = x if j % 2 == 0 else x[::-1]
        y = 4.0 * j + 0.02 * x
        z = 120 + 8 * np.sin(x / 60) * np.cos(y / 45)
        rows.append(np.column_stack([x + 512000.0, y + 5400000.0, z]))
    return rows


def write_las(path, rows, fmt=1, version=(1, 2), scale=0.001, edge=True, direction=True,
              compressed=False, truncate=0):
    """A LAS file written to the ASPRS specification: the public header block, no VLRs, and
    point records of format `fmt` carrying the scan direction and edge-of-flight-line flags."""
    pts = np.concatenate(rows)
    offset = np.floor(pts.min(axis=0))
    raw = np.round((pts - offset) / scale).astype("<i4")
    record = {0: 20, 1: 28, 6: 30}[fmt]
    header_size = 375 if version >= (1, 4) else 227
    h = bytearray(header_size)
    h[0:4] = b"LASF"
    h[24], h[25] = version
    struct.pack_into("<H", h, 94, header_size)
    struct.pack_into("<I", h, 96, header_size)
    h[104] = fmt | (0x80 if compressed else 0)
    struct.pack_into("<H", h, 105, record)
    struct.pack_into("<I", h, 107, len(pts) if fmt < 6 else 0)
    struct.pack_into("<3d", h, 131, scale, scale, scale)
    struct.pack_into("<3d", h, 155, *offset)
    struct.pack_into("<6d", h, 179, *[v for a in range(3) for v in (pts[:, a].max(), pts[:, a].min())])
    if version >= (1, 4):
        struct.pack_into("<Q", h, 247, len(pts))
    rec = np.zeros((len(pts), record), dtype=np.uint8)
    rec[:, 0:12] = raw.view(np.uint8).reshape(len(pts), 12)
    k = 0
    for j, r in enumerate(rows):
        flags = np.zeros(len(r), dtype=np.uint8)
        if direction and j % 2:
            flags |= 0x40
        if edge:
            flags[-1] |= 0x80
        rec[k:k + len(r), 14 if fmt < 6 else 15] = flags
        k += len(r)
    data = bytes(h) + rec.tobytes()
    path.write_bytes(data[:len(data) - truncate])
    return [(r - offset) / scale for r in rows], offset, scale


@pytest.mark.parametrize("fmt,version", [(0, (1, 0)), (1, (1, 2)), (6, (1, 4))])
@pytest.mark.parametrize("flags", ["edge", "direction", "both"])
def test_points_and_scan_lines_come_back_across_pieces(tmp_path, fmt, version, flags):
    rows = scan()
    path = tmp_path / "strip.las"
    scaled, offset, scale = write_las(path, rows, fmt=fmt, version=version,
                                      edge=flags != "direction", direction=flags != "edge")
    # Two files (the second's rows follow), in pieces of whole lines of at most 97 points.
    x = sfit.dask.points_from_files([path, path], las_chunk_points=97)
    got = x.compute()
    # Every row as written, the lines run backwards turned round, rounded to the file's scale.
    stored = [np.round(r) * scale + offset for r in scaled]
    stored = [r if j % 2 == 0 else r[::-1] for j, r in enumerate(stored)]
    want = np.concatenate([np.column_stack([r, np.full(len(r), j)])
                           for j, r in enumerate(stored + stored)])
    np.testing.assert_array_equal(got[:, 3], want[:, 3])
    np.testing.assert_allclose(got[:, :3], want[:, :3], rtol=0, atol=1e-9)
    back = [r if j % 2 == 0 else r[::-1] for j, r in enumerate(rows)]
    assert np.max(np.abs(got[: len(got) // 2, :3] - np.concatenate(back))) <= scale / 2 + 1e-9
    # Pieces of whole lines, at most 97 points unless one line is longer.
    ends = np.cumsum(x.chunks[0])
    line_starts = set(np.flatnonzero(np.diff(want[:, 3])) + 1) | {len(want)}
    assert all(int(e) in line_starts for e in ends)
    assert len(x.chunks[0]) > 2 * len(rows) // 3
    assert all(c <= 97 or np.unique(got[e - c:e, 3]).size == 1
               for c, e in zip(x.chunks[0], ends))


def test_a_las_strip_fits_as_its_rows_do_in_memory(tmp_path, monkeypatch):
    rows = scan(lines=31)
    path = tmp_path / "strip.las"
    write_las(path, rows, fmt=6, version=(1, 4))
    monkeypatch.setattr(sfit._dask_input, "LAS_CHUNK_POINTS", 500)
    stored = sfit.dask.points_from_files([path]).compute()
    cut = np.flatnonzero(np.diff(stored[:, 3])) + 1
    as_read = [r[:, :3] for r in np.split(stored, cut)]
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as c, distributed.Client(c):
        got = sfit.dask.fit([str(path)], tol_rel=1e-3, closed="")
    assert got.report["within_tolerance"] and got.report["rows"] == 31
    mem = sfit.dask.in_memory_fit(as_read, got.report["control_points"],
                                  tol=got.report["tolerance"])
    d = np.max(np.abs(got.surface.control_points - mem.surface.control_points))
    assert d / np.max(np.abs(mem.surface.control_points)) < 1e-10


def test_faults_are_named(tmp_path):
    rows = scan(lines=5)
    cases = {
        "laz.las": (dict(compressed=True), "compressed \\(LAZ\\)", "input-syntax"),
        "short.las": (dict(truncate=7), "promises .* points, the file holds", "input-syntax"),
        "noflags.las": (dict(edge=False, direction=False), "no point sets the scan direction",
                        "input-data"),
    }
    for name, (kw, match, code) in cases.items():
        path = tmp_path / name
        write_las(path, rows, **kw)
        with pytest.raises(sfit.Error, match=match) as e:
            sfit.dask.points_from_files([path])
        assert e.value.code == code and e.value.file == str(path)
    other = tmp_path / "not.las"
    other.write_text("1 2 3\n" * 100)
    with pytest.raises(sfit.Error, match="not a LAS file") as e:
        _las.Header(other)
    assert e.value.exit_code == 4
