"""sfit.dask: one surface from points spread over a Dask cluster (docs/python.md, "More than
one machine").

The least-squares surface at a pair of counts (nu, nv) is a sum over the points: each chunk of
points gives its part of the normal equations (the band of A^T A and the right-hand sides
A^T z for x, y and z, computed on the worker by the library's own basis code), the parts are
summed by Dask's tree reduction, the client solves the sum (the library's solver), and the
check (the largest deviation per axis) is a maximum mapped over the chunks. The count search
drives rounds of this. The result equals the in-memory fit at the same counts
(`in_memory_fit`, the library's fixed-counts fit) to 1e-10 relative, whatever the chunking.

    import dask.array as da, sfit.dask
    from distributed import Client
    client = Client("tcp://scheduler:8786")        # or Client(LocalCluster())
    points = da.from_zarr(...)                      # (n, 4): x, y, z, row
    fit = sfit.dask.fit(points, tol_rel=1e-3)
    fit.surface, fit.report

Points: rows of a scan numbered 0 ... M-1, the points of each row stored consecutively and in
order along the row, the rows in order (a row may span chunks). Parameters: the uniform rule
(equal steps in the point's index along each row, equal steps across the rows) or the paper's;
both need only each row's point count, gathered in a first pass.
"""

import math
import time

import numpy as np

from . import _sfit
from ._errors import Error

__all__ = ["DaskFit", "fit", "in_memory_fit", "points_from_files", "partial_bytes"]

# No task result over this many bytes (one chunk's normal equations grow with nu nv).
MAX_RESULT_BYTES = 256 << 20


def _error(code, message, **place):
    e = Error(message)
    e.code = code
    e.exit_code = {"usage": 2, "input-unreadable": 3, "input-data": 5,
                   "tolerance-not-met": 7}.get(code, 8)
    for k, v in place.items():
        setattr(e, k, v)
    return e


def partial_bytes(nu, nv, degree_u=3, degree_v=3):
    """Bytes of one chunk's normal equations at (nu, nv): what each task sends back."""
    return 8 * _sfit._partial_size(nu, nv, degree_u, degree_v)


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


def points_from_files(paths):
    """A dask array (n, 4) of the points of `paths` (.rows, .srows, .npy, .las), each read by
    the worker that computes it: one chunk per file, a LAS file in pieces of whole scan lines
    of at most LAS_CHUNK_POINTS points; the rows of a file follow those of the file before (a
    LAS file's rows are its scan lines, all turned to run one way: sfit/_las.py). One pass
    reads every file once on the workers to learn its size (of a LAS file, the flags of its
    points)."""
    import dask
    import dask.array as da

    from . import _las

    paths = [str(p) for p in paths]
    if not paths:
        raise _error("usage", "no files given", option="points")
    shapes = dask.compute(*[
        dask.delayed(_las.scan_lines, pure=True)(p, LAS_CHUNK_POINTS) if _is_las(p)
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


# ---------------------------------------------------------------------------- the tasks

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


def _partial(block, info, centre, nu, nv, spec):
    return _sfit._partial_normal_equations(block, info[0], info[1], info[2], info[3], info[4],
                                           centre, nu, nv, *spec)


def _deviation(block, info, centre, control, spec):
    return _sfit._chunk_deviation(block, info[0], info[1], info[2], info[3], info[4], centre,
                                  control, *spec)


# ---------------------------------------------------------------------------- the client

class DaskFit:
    """The result of sfit.dask.fit(): `surface` (an sfit.Surface), `report` (a dict with the
    keys of sfit.Fit.report that apply), `v` (the parameter of every row), `row_sizes`,
    `pairs` (every (nu, nv) tried and whether it held, in order)."""

    def __init__(self, surface, report, v, row_sizes, pairs):
        self.surface, self.report, self.v, self.row_sizes, self.pairs = \
            surface, report, v, row_sizes, pairs

    def __repr__(self):
        r = self.report
        return (f"<sfit.dask.DaskFit {r['control_points'][0]} x {r['control_points'][1]} "
                f"control points, {r['rows']} rows, {r['points']} points, within tolerance: "
                f"{'yes' if r['within_tolerance'] else 'no'}>")


class _Runner:
    """Computes collections on the default Dask scheduler (a distributed Client where one is
    active), with distributed.progress() when asked."""

    def __init__(self, progress):
        self.progress = progress
        try:
            from distributed import default_client
            self.client = default_client()
        except (ImportError, ValueError):
            self.client = None

    def __call__(self, *collections):
        import dask

        if self.client is None:
            return dask.compute(*collections)
        futures = self.client.compute(list(collections))
        if self.progress:
            from distributed import progress
            progress(futures)
        return self.client.gather(futures)


def fit(points, tol=None, tol_rel=None, degree=3, degree_u=None, degree_v=None, closed="",
        parameters="uniform", rows=None, counts=None, split_every=8, progress=False):
    """One surface from points spread over a Dask cluster.

    points: a dask.array (n, 4) of x, y, z, row; or (n, 3) with `rows` (n,); or a
    dask.dataframe with columns x, y, z, row; or a list of files (.rows, .srows, .npy), each a
    chunk read by its worker. The points of a row are consecutive and in order, the rows in
    order, numbered 0 ... M-1 (a row may span chunks).
    tol / tol_rel: T, as sfit.fit (default 1e-3 of the bounding-box diagonal).
    parameters: "uniform" (default) or "paper". counts: (nu, nv) to fit at, no search.
    split_every: the tree reduction's fan-in. progress: distributed.progress() per pass.
    Returns a DaskFit equal to in_memory_fit() of the same points at the same counts. Raises
    sfit.Error ("usage", "input-data", "tolerance-not-met" when no pair holds T).
    """
    import dask
    import dask.array as da

    t0 = time.perf_counter()
    du = degree if degree_u is None else degree_u
    dv = degree if degree_v is None else degree_v
    for name, d in (("degree_u", du), ("degree_v", dv)):
        if not isinstance(d, int) or not 1 <= d <= 20:
            raise _error("usage", f"{name}: {d!r} is not 1 ... 20", option=name)
    if closed not in ("", "none", "u", "v", "uv"):
        raise _error("usage", f"closed: '{closed}' is not one of u, v, uv, none",
                     option="closed")
    cu, cv = "u" in closed, "v" in closed
    if parameters not in ("uniform", "paper"):
        raise _error("usage", f"parameters: '{parameters}' is not one of uniform, paper "
                     "(the rules a distributed fit reproduces exactly)", option="parameters")
    if tol is not None and tol_rel is not None:
        raise _error("usage", "give tol or tol_rel, not both", option="tol_rel")
    run = _Runner(progress)
    X = _as_points(points, rows)

    # Pass 1: the box and each row's points (a row may span chunks).
    blocks = list(X.to_delayed().ravel())
    stats = run(*[dask.delayed(_block_stats, pure=True)(b) for b in blocks])
    sizes_of_chunks = np.array(X.chunks[0], dtype=np.int64)
    g0 = np.concatenate([[0], np.cumsum(sizes_of_chunks)])[:-1]
    used = [i for i, s in enumerate(stats) if s is not None]
    for i in used:
        if "error" in stats[i]:
            raise _error("input-data", f"chunk {i}: {stats[i]['error']}")
    if not used:
        raise _error("input-data", "no points")
    for a, b in zip(used, used[1:]):
        if stats[b]["rows"][0] < stats[a]["rows"][-1]:
            raise _error("input-data", f"rows out of order between chunks {a} and {b}: row "
                         f"{stats[b]['rows'][0]} after row {stats[a]['rows'][-1]}")
    M = int(stats[used[-1]]["rows"][-1]) + 1
    row_sizes = np.zeros(M, dtype=np.int64)
    for i in used:
        np.add.at(row_sizes, stats[i]["rows"], stats[i]["counts"])
    empty = np.flatnonzero(row_sizes == 0)
    if len(empty):
        raise _error("input-data", f"row {empty[0]} has no points (rows are numbered "
                     f"0 ... {M - 1})", row=int(empty[0]))
    if M < dv + 1 and not cv or M < 2:
        raise _error("input-data", f"{M} rows: a surface of degree {dv} across the rows needs "
                     f"{dv + 1}")
    row_starts = np.concatenate([[0], np.cumsum(row_sizes)])[:-1]
    box_min = np.min([stats[i]["min"] for i in used], axis=0)
    box_max = np.max([stats[i]["max"] for i in used], axis=0)
    centre = 0.5 * (box_min + box_max)
    diag = math.sqrt(float(np.sum((box_max - box_min) ** 2)))
    if tol is not None:
        T = np.broadcast_to(np.asarray(tol, dtype=float), (3,)).copy()
    else:
        T = np.full(3, (1e-3 if tol_rel is None else float(tol_rel)) * diag)
    if not np.all(T >= 0):
        raise _error("usage", f"tol must be >= 0, got {T.tolist()}", option="tol")
    roundoff = 1e-10 * diag
    n_points = int(row_sizes.sum())

    # Per chunk: where it starts, its first row, and its rows' starts and sizes.
    infos = []
    for i, b in enumerate(blocks):
        if stats[i] is None:
            infos.append(None)
            continue
        r0, r1 = int(stats[i]["rows"][0]), int(stats[i]["rows"][-1]) + 1
        infos.append((int(g0[i]), r0, row_starts[r0:r1], row_sizes[r0:r1], M))
    work = [(b, info) for b, info in zip(blocks, infos) if info is not None]
    spec = (du, dv, cu, cv, parameters)
    pairs = []
    max_u = max(du + 1, int(row_sizes.max()))
    max_v = max(dv + 1, M)

    def solve(nu, nv):
        """One round at (nu, nv): partial normal equations tree-reduced, solved here."""
        nbytes = partial_bytes(nu, nv, du, dv)
        if nbytes > MAX_RESULT_BYTES:
            raise _error("usage", f"{nu} x {nv} control points: one chunk's normal equations "
                         f"would be {nbytes / 2**20:.0f} MiB, above the 256 MiB a task may "
                         "return", option="counts")
        parts = [da.from_delayed(dask.delayed(_partial, pure=True)(b, info, centre, nu, nv,
                                                                    spec),
                                 shape=(nbytes // 8,), dtype=float) for b, info in work]
        total = da.stack(parts).sum(axis=0, split_every=split_every)
        (flat,) = run(total)
        ok, control, guard = _sfit._solve_normal_equations(
            flat, nu, nv, du, dv, cu, cv, int(row_sizes.min()), box_min, box_max)
        return control if ok else None, guard

    def check(control):
        """The largest deviation per axis, mapped over the chunks, max-reduced."""
        c = dask.delayed(control, pure=True)
        parts = [da.from_delayed(dask.delayed(_deviation, pure=True)(b, info, centre, c, spec),
                                 shape=(3,), dtype=float) for b, info in work]
        (dev,) = run(da.stack(parts).max(axis=0, split_every=split_every))
        return dev

    def attempt(nu, nv):
        control, guard = solve(nu, nv)
        dev = check(control) if control is not None else None
        # The round-off allowance only on an axis whose T is 0, as in the library.
        holds = dev is not None and guard is None and bool(
            np.all(dev <= T + np.where(T == 0, roundoff, 0.0)))
        pairs.append({"counts": [nu, nv], "holds": holds,
                      "max_deviation": None if dev is None else dev.tolist(),
                      "guard": guard})
        return holds, control, dev

    results = {}

    def holds_at(nu, nv):
        if (nu, nv) not in results:
            results[(nu, nv)] = attempt(nu, nv)
        return results[(nu, nv)][0]

    if counts is not None:
        nu, nv = (int(c) for c in counts)
        if nu < du + 1 or nv < dv + 1:
            raise _error("usage", f"counts ({nu}, {nv}) below degree + 1", option="counts")
        holds_at(nu, nv)
    else:
        # Gallop both counts up from degree + 1 until the surface holds, then bisect nu at
        # that nv, then nv at the nu found (each probe one round over the data). Holding is not
        # monotone in the counts (the parameters move with them): the bisection finds a count
        # that holds with the one below failing, as the library's search does.
        nu, nv = min(max_u, 2 * (du + 1)), min(max_v, 2 * (dv + 1))
        while not holds_at(nu, nv):
            if nu == max_u and nv == max_v:
                raise _error("tolerance-not-met", f"no surface within T up to {nu} x {nv} "
                             "control points (the largest the data allows)")
            nu, nv = min(max_u, 2 * nu), min(max_v, 2 * nv)
        lo, hi = du, nu  # lo: below the smallest count
        while hi - lo > 1:
            mid = (lo + hi) // 2
            lo, hi = (lo, mid) if holds_at(mid, nv) else (mid, hi)
        nu = hi
        lo, hi = dv, nv
        while hi - lo > 1:
            mid = (lo + hi) // 2
            lo, hi = (lo, mid) if holds_at(nu, mid) else (mid, hi)
        nv = hi
    holds, control, dev = results[(nu, nv)]
    if control is None:
        raise _error("tolerance-not-met", f"no surface with {nu} x {nv} control points: a knot "
                     "span has no data", option="counts")
    surface = _sfit._surface_from_control(control, du, dv, cu, cv, centre)
    v = _sfit._row_parameters(M, nv, dv, cv, parameters)
    report = {
        "points": n_points, "rows": M, "tolerance": T.tolist(),
        "max_deviation": dev.tolist(), "within_tolerance": holds,
        "control_points": [nu, nv], "degree": [du, dv], "closed": [cu, cv],
        "parametrization": parameters, "method": "dask least squares",
        "pairs_tried": len(pairs), "chunks": len(work),
        "partial_bytes": partial_bytes(nu, nv, du, dv),
        "roundoff": roundoff, "seconds": time.perf_counter() - t0,
    }
    return DaskFit(surface, report, v, row_sizes, pairs)


def in_memory_fit(rows, counts, tol, degree=3, degree_u=None, degree_v=None, closed="",
                  parameters="uniform", threads=0):
    """The library's in-memory least-squares fit of `rows` (a list of (N_j, 3) arrays) at
    exactly `counts` (FitOptions::counts, least squares, one rule, seams and orientation as
    given): an sfit.Fit, what fit() equals for the same points."""
    du = degree if degree_u is None else degree_u
    dv = degree if degree_v is None else degree_v
    return _sfit._fit_at_counts(rows, int(counts[0]), int(counts[1]), tol, du, dv,
                                "u" in closed, "v" in closed, parameters, threads)
