"""The input of sfit.dask: files, arrays and dataframes as one dask array (n, 4) of x, y, z,
row, and the first pass over it (each chunk's box and rows)."""

import math

import numpy as np

from . import _sfit
from ._errors import Error

def _error(code, message, **place):
    e = Error(message)
    e.code = code
    e.exit_code = {"usage": 2, "input-unreadable": 3, "input-data": 5,
                   "tolerance-not-met": 7}.get(code, 8)
    for k, v in place.items():
        setattr(e, k, v)
    return e


def _given_counts(counts, du, dv):
    """counts=(nu, nv) as ints, each at least degree + 1 (else a usage error)."""
    nu, nv = (int(c) for c in counts)
    if nu < du + 1 or nv < dv + 1:
        raise _error("usage", f"counts ({nu}, {nv}) below degree + 1", option="counts")
    return nu, nv


# ---------------------------------------------------------------------------- the input

def _read_file(path, row_offset):
    """Worker task: one file as an (n, 4) array (x, y, z, row), rows numbered from
    `row_offset`."""
    if str(path).endswith(".npy"):
        a = np.load(path)
        if a.ndim == 3 and a.shape[2] == 3:  # a grid: (M, N, 3)
            rows = np.repeat(np.arange(a.shape[0], dtype=float), a.shape[1])
            return np.column_stack([a.reshape(-1, 3).astype(float), rows + row_offset])
        if a.ndim == 2 and a.shape[1] == 4:
            a = a.astype(float)
            a[:, 3] += row_offset
            return a
        raise _error("input-data", f"{path}: expected an (n, 4) array (x, y, z, row) or an "
                     f"(M, N, 3) grid, got shape {a.shape}", file=str(path))
    rows = _sfit.load_rows(str(path))  # .rows, .srows, ...: the CLI's reader
    n = sum(len(r) for r in rows)
    out = np.empty((n, 4))
    k = 0
    for j, r in enumerate(rows):
        out[k:k + len(r), :3] = r
        out[k:k + len(r), 3] = row_offset + j
        k += len(r)
    return out


def _file_shape(path):
    """Worker task: (points, rows) of one file."""
    a = _read_file(path, 0)
    return a.shape[0], (int(a[-1, 3]) + 1 if len(a) else 0)


def _is_las(path):
    return str(path).lower().endswith(".las")


# A LAS file is read in pieces of this many points (128 MB as the (n, 4) float64 chunk).
LAS_CHUNK_POINTS = 4 << 20


def points_from_files(paths, las_chunk_points=None):
    """A dask array (n, 4) of the points of `paths` (.rows, .srows, .npy, .las), each read by
    the worker that computes it: one chunk per file, a LAS file in pieces of whole scan lines
    of at most LAS_CHUNK_POINTS points; the rows of a file follow those of the file before (a
    LAS file's rows are its scan lines, all turned to run one way: sfit/_las.py;
    `las_chunk_points`: another piece size). One pass
    reads every file once on the workers to learn its size (of a LAS file, the flags of its
    points)."""
    import dask
    import dask.array as da

    from . import _las

    paths = [str(p) for p in paths]
    if not paths:
        raise _error("usage", "no files given", option="points")
    shapes = dask.compute(*[
        dask.delayed(_las.scan_lines, pure=True)(p, las_chunk_points or LAS_CHUNK_POINTS) if _is_las(p)
        else dask.delayed(_file_shape, pure=True)(p) for p in paths])
    blocks = []
    rows_before = 0
    for p, shape in zip(paths, shapes):
        if not _is_las(p):
            blocks.append(da.from_delayed(dask.delayed(_read_file, pure=True)(p, rows_before),
                                          shape=(shape[0], 4), dtype=float))
            rows_before += shape[1]
            continue
        reference, pieces = shape
        for first, count, lines in pieces:
            blocks.append(da.from_delayed(
                dask.delayed(_las.read_points, pure=True)(p, first, count, rows_before,
                                                          reference),
                shape=(count, 4), dtype=float))
            rows_before += lines
    return da.concatenate(blocks, axis=0)


def _as_points(points, rows):
    """The input as one dask array (n, 4) of float64 chunked along the points only."""
    import dask.array as da

    if isinstance(points, (list, tuple)) and points and isinstance(points[0], str) or \
            (isinstance(points, (list, tuple)) and points and hasattr(points[0], "__fspath__")):
        return points_from_files(points)
    if hasattr(points, "to_dask_array") and hasattr(points, "columns"):  # dask.dataframe
        missing = [c for c in ("x", "y", "z", "row") if c not in points.columns]
        if missing:
            raise _error("usage", f"the dataframe lacks column(s) {', '.join(missing)}",
                         option="points")
        points = points[["x", "y", "z", "row"]].to_dask_array(lengths=True)
    if not isinstance(points, da.Array):
        points = da.from_array(np.asarray(points))
    if rows is not None:
        if points.ndim != 2 or points.shape[1] != 3:
            raise _error("usage", f"with rows, points must be (n, 3), got {points.shape}",
                         option="points")
        rows = rows if isinstance(rows, da.Array) else da.from_array(np.asarray(rows))
        if rows.shape != (points.shape[0],):
            raise _error("usage", f"rows must have one entry per point, got {rows.shape}",
                         option="rows")
        rows = rows.rechunk((points.chunks[0],))
        points = da.concatenate([points.astype(float), rows[:, None].astype(float)], axis=1)
    if points.ndim != 2 or points.shape[1] != 4:
        raise _error("usage", f"points must be (n, 4) (x, y, z, row), or (n, 3) with rows; got "
                     f"{points.shape}", option="points")
    if any(math.isnan(c) for c in points.chunks[0]):
        points = points.compute_chunk_sizes()
    return points.astype(float).rechunk({1: 4})


def _block_stats(block):
    """Worker task: the box, and the rows of a chunk with their points (rows consecutive)."""
    if len(block) == 0:
        return None
    if not np.all(np.isfinite(block)):
        bad = int(np.argmax(~np.all(np.isfinite(block), axis=1)))
        return {"error": f"a non-finite number at chunk point {bad}"}
    r = block[:, 3]
    if np.any(r != np.floor(r)) or r[0] < 0:
        return {"error": "row numbers must be integers >= 0"}
    d = np.diff(r)
    if np.any(d < 0):
        k = int(np.argmax(d < 0))
        return {"error": f"rows out of order: row {int(r[k + 1])} after row {int(r[k])} (the "
                "points of a row must be consecutive, the rows in order)"}
    cut = np.flatnonzero(d) + 1
    starts = np.concatenate([[0], cut])
    counts = np.diff(np.concatenate([starts, [len(r)]]))
    return {"min": block[:, :3].min(axis=0), "max": block[:, :3].max(axis=0),
            "rows": r[starts].astype(np.int64), "counts": counts.astype(np.int64)}
