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
both need only each row's point count, gathered in a first pass. Or the geometric rule
(_dask_geometric.py: each point's (u, v) from a base plane, corrected by projection onto the
fit; the per-point parameters stay on the workers).
"""

import math
import time

import numpy as np

from . import _sfit
from ._dask_input import (LAS_CHUNK_POINTS, _as_points, _block_stats, _error,
                          _given_counts, points_from_files)
from ._dask_tasks import (_deviation, _first_pass, _partial, _rows_sample, _sample_of,
                          _stats_of)

__all__ = ["DaskFit", "LAS_CHUNK_POINTS", "fit", "in_memory_fit", "points_from_files",
           "partial_bytes"]

# No task result over this many bytes (one chunk's normal equations grow with nu nv).
MAX_RESULT_BYTES = 256 << 20
# Control points up to this size travel inside each check task (fused with the chunk's read).
INLINE_CONTROL_BYTES = 1 << 20
# Above this many points the count search runs on a sample of the rows (fit(sample_points=)).
SAMPLE_POINTS = 2_000_000


def partial_bytes(nu, nv, degree_u=3, degree_v=3):
    """Bytes of one chunk's normal equations at (nu, nv): what each task sends back."""
    return 8 * _sfit._partial_size(nu, nv, degree_u, degree_v)


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
    active), with distributed.progress() when asked; logs each pass (what, rows step,
    seconds of wall) for the report."""

    def __init__(self, progress):
        self.progress = progress
        self.log = []
        try:
            from distributed import default_client
            self.client = default_client()
        except (ImportError, ValueError):
            self.client = None

    def persist(self, what, step, *collections):
        """Persists on the workers and waits (so the pass is timed as itself)."""
        import dask

        t = time.perf_counter()
        if self.client is None:
            out = dask.persist(*collections)
        else:
            from distributed import futures_of, wait

            out = self.client.persist(list(collections))
            if self.progress:
                from distributed import progress
                progress(out)
            wait(futures_of(out))
        self.log.append({"pass": what, "rows_step": step,
                         "seconds": round(time.perf_counter() - t, 3)})
        return out

    def __call__(self, what, step, *collections):
        import dask

        t = time.perf_counter()
        if self.client is None:
            out = dask.compute(*collections)
        else:
            futures = self.client.compute(list(collections))
            if self.progress:
                from distributed import progress
                progress(futures)
            out = self.client.gather(futures)
        if what is not None:  # None: no pass over the points (results already on the workers)
            self.log.append({"pass": what, "rows_step": step,
                             "seconds": round(time.perf_counter() - t, 3)})
        return out


def fit(points, tol=None, tol_rel=None, degree=3, degree_u=None, degree_v=None, closed="",
        parameters="uniform", rows=None, counts=None, split_every=8, progress=False,
        sample_points=SAMPLE_POINTS):
    """One surface from points spread over a Dask cluster.

    points: a dask.array (n, 4) of x, y, z, row; or (n, 3) with `rows` (n,); or a
    dask.dataframe with columns x, y, z, row; or a list of files (.rows, .srows, .npy), each a
    chunk read by its worker. The points of a row are consecutive and in order, the rows in
    order, numbered 0 ... M-1 (a row may span chunks).
    tol / tol_rel: T, as sfit.fit (default 1e-3 of the bounding-box diagonal).
    parameters: "uniform" (default), "paper" or "geometric" (open rows only; DaskFit.v is
    then None: v is per point and stays on the workers). counts: (nu, nv) to fit at, no search.
    split_every: the tree reduction's fan-in. progress: distributed.progress() per pass.
    sample_points: above this many points the counts are searched on every k-th row (about
    this many points; kept by each chunk's worker from the statistics' pass), then verified
    on every point and raised until they hold there (coarse to fine: three passes over all
    the points in all where the sample's pair holds).
    Returns a DaskFit (its report's "passes": every pass with its row step and seconds) equal
    to in_memory_fit() of the same points at the same counts. Raises sfit.Error ("usage",
    "input-data", "tolerance-not-met" when no pair holds T).
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
    if parameters not in ("uniform", "paper", "geometric"):
        raise _error("usage", f"parameters: '{parameters}' is not one of uniform, paper, "
                     "geometric (the rules a distributed fit reproduces)", option="parameters")
    if parameters == "geometric" and (cu or cv):
        raise _error("usage", "parameters geometric: open rows, open across only in sfit.dask "
                     "(closed rows take the swept axis of the in-memory fit)", option="closed")
    if tol is not None and tol_rel is not None:
        raise _error("usage", "give tol or tol_rel, not both", option="tol_rel")
    run = _Runner(progress)
    X = _as_points(points, rows)

    # Pass 1: the box and each row's points (a row may span chunks); above sample_points, in
    # the same pass, each chunk's points of every step-th row kept on its worker for the search.
    blocks = list(X.to_delayed().ravel())
    step_n = 1
    if counts is None and X.shape[0] > sample_points and parameters != "geometric":
        step_n = -(-X.shape[0] // sample_points)
    firsts = None
    if step_n == 1:
        stats = run("statistics", 1,
                    *[dask.delayed(_block_stats, pure=True)(b) for b in blocks])
    else:
        firsts = run.persist(f"statistics, sample of every {step_n}th row", 1,
                             *[dask.delayed(_first_pass, pure=True)(b, step_n)
                               for b in blocks])
        stats = run(None, 0, *[dask.delayed(_stats_of, pure=True)(f) for f in firsts])
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
    if firsts is not None:
        firsts = [f for f, info in zip(firsts, infos) if info is not None]
    if parameters == "geometric":
        from ._dask_geometric import fit_after_statistics
        return fit_after_statistics(run, work, centre, box_min, box_max, T, roundoff, du, dv,
                                    split_every, counts, n_points, M, row_sizes, t0)
    spec = (du, dv, cu, cv, parameters)
    pairs = []
    max_u = max(du + 1, int(row_sizes.max()))
    max_v = max(dv + 1, M)

    def solve(nu, nv, step):
        """One round at (nu, nv) over every step-th row: partial normal equations
        tree-reduced, solved here."""
        nbytes = partial_bytes(nu, nv, du, dv)
        if nbytes > MAX_RESULT_BYTES:
            raise _error("usage", f"{nu} x {nv} control points: one chunk's normal equations "
                         f"would be {nbytes / 2**20:.0f} MiB, above the 256 MiB a task may "
                         "return", option="counts")
        parts = [da.from_delayed(dask.delayed(_partial, pure=True)(c, centre, nu, nv, spec),
                                 shape=(nbytes // 8,), dtype=float) for c in chunks_at[step]]
        total = da.stack(parts).sum(axis=0, split_every=split_every)
        (flat,) = run(f"normal equations {nu} x {nv}", step, total)
        kept = row_sizes[(np.arange(M) % step == 0) | (np.arange(M) == M - 1)]
        ok, control, guard = _sfit._solve_normal_equations(
            flat, nu, nv, du, dv, cu, cv, int(kept.min()), box_min, box_max)
        return control if ok else None, guard

    def check(control, nu, nv, step):
        """The largest deviation per axis, mapped over the chunks, max-reduced. Small control
        points go into each task (so Dask fuses the check into the task that reads or makes
        the chunk, as it does the normal equations: a task with a second input, shared,
        would not fuse, and the chunk could travel to another worker), larger ones once as a
        shared input."""
        c = control if control.nbytes <= INLINE_CONTROL_BYTES else \
            dask.delayed(control, pure=True)
        parts = [da.from_delayed(dask.delayed(_deviation, pure=True)(w, centre, c, spec),
                                 shape=(3,), dtype=float) for w in chunks_at[step]]
        (dev,) = run(f"check {nu} x {nv}", step,
                     da.stack(parts).max(axis=0, split_every=split_every))
        return dev

    def attempt(nu, nv, step):
        control, guard = solve(nu, nv, step)
        dev = check(control, nu, nv, step) if control is not None else None
        # The round-off allowance only on an axis whose T is 0, as in the library.
        holds = dev is not None and guard is None and bool(
            np.all(dev <= T + np.where(T == 0, roundoff, 0.0)))
        pairs.append({"counts": [nu, nv], "holds": holds, "rows_step": step,
                      "max_deviation": None if dev is None else dev.tolist(),
                      "guard": guard})
        return holds, control, dev

    results = {}

    def holds_at(nu, nv, step=1):
        if (nu, nv, step) not in results:
            results[(nu, nv, step)] = attempt(nu, nv, step)
        return results[(nu, nv, step)][0]

    def search(step, top_v):
        """Gallop both counts up from degree + 1 until the surface holds, then bisect nu at
        that nv, then nv at the nu found (each probe one round over the data). Holding is not
        monotone in the counts (the parameters move with them): the bisection finds a count
        that holds with the one below failing, as the library's search does."""
        nu, nv = min(max_u, 2 * (du + 1)), min(top_v, 2 * (dv + 1))
        while not holds_at(nu, nv, step):
            if nu == max_u and nv == top_v:
                return None
            nu, nv = min(max_u, 2 * nu), min(top_v, 2 * nv)
        lo, hi = du, nu  # lo: below the smallest count
        while hi - lo > 1:
            mid = (lo + hi) // 2
            lo, hi = (lo, mid) if holds_at(mid, nv, step) else (mid, hi)
        nu = hi
        lo, hi = dv, nv
        while hi - lo > 1:
            mid = (lo + hi) // 2
            lo, hi = (lo, mid) if holds_at(nu, mid, step) else (mid, hi)
        return nu, hi

    # Coarse to fine: the search on every step-th row (at least 64 rows and 4 per control
    # point across), then the pair on every point, raised by an eighth until it holds there.
    step = 1
    if counts is None and n_points > sample_points:
        step = max(1, min(-(-n_points // sample_points), (M - 1) // max(64, 4 * (dv + 1))))
    # Each chunk as (points, rows); the sample's filtered once by its worker and kept there
    # (persisted: a probe on it reads 1/step of the points, not the chunk again).
    chunks_at = {1: [dask.delayed(_rows_sample, pure=True)(b, info, 1) for b, info in work]}
    if step > 1 and step == step_n:  # made in pass 1
        chunks_at[step] = list(run.persist(
            f"sample of every {step}th row", step,
            *[dask.delayed(_sample_of, pure=True)(f, info, step)
              for f, (b, info) in zip(firsts, work)]))
    elif step > 1:  # fewer rows than pass 1 assumed: a pass of its own
        chunks_at[step] = list(run.persist(
            f"sample of every {step}th row", 1,
            *[dask.delayed(_rows_sample, pure=True)(b, info, step) for b, info in work]))
    firsts = None  # pass 1's points released where the sample was made (or not needed)
    stop = "minimal"
    if counts is not None:
        nu, nv = _given_counts(counts, du, dv)
        holds_at(nu, nv)
        stop = "counts given"
    else:
        found = search(step, max_v if step == 1 else min(max_v, 1 + (M - 1) // step))
        if found is None and step > 1:
            step, found = 1, search(1, max_v)
        if found is None:
            raise _error("tolerance-not-met", f"no surface within T up to {max_u} x {max_v} "
                         "control points (the largest the data allows)")
        nu, nv = found
        if step > 1:
            while not holds_at(nu, nv):
                if nu == max_u and nv == max_v:
                    raise _error("tolerance-not-met", f"no surface within T up to {nu} x {nv} "
                                 "control points (the largest the data allows)")
                # Up by an eighth: one count, the other, then both (fewest control points first).
                up_u, up_v = min(max_u, nu + max(1, nu // 8)), min(max_v, nv + max(1, nv // 8))
                for a, b in sorted({(nu, up_v), (up_u, nv)} - {(nu, nv)},
                                   key=lambda c: (c[0] * c[1], c)):
                    if holds_at(a, b):
                        nu, nv = a, b
                        break
                else:
                    nu, nv = up_u, up_v
            stop = (f"minimal on every {step}th row, verified on every point" if
                    (nu, nv) == found else f"raised from {found[0]} x {found[1]} (minimal on "
                    f"every {step}th row) until every point held")
    holds, control, dev = results[(nu, nv, 1)]
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
        "pairs_tried": len(pairs), "chunks": len(work), "stop_reason": stop,
        "rows_step": step, "full_passes": sum(p["rows_step"] == 1 for p in run.log),
        "passes": run.log,
        "partial_bytes": partial_bytes(nu, nv, du, dv),
        "roundoff": roundoff, "seconds": time.perf_counter() - t0,
    }
    return DaskFit(surface, report, v, row_sizes, pairs)


def in_memory_fit(rows, counts, tol, degree=3, degree_u=None, degree_v=None, closed="",
                  parameters="uniform", threads=0):
    """The library's in-memory least-squares fit of `rows` (a list of (N_j, 3) arrays) at
    exactly `counts` (FitOptions::counts, least squares, one rule, seams and orientation as
    given): an sfit.Fit, what fit() equals for the same points. parameters: "uniform",
    "paper" or "geometric" (the library's geometric_at_counts(): base plane, the smoothness
    weight lowered where needed, corrections while the worst deviation falls)."""
    du = degree if degree_u is None else degree_u
    dv = degree if degree_v is None else degree_v
    return _sfit._fit_at_counts(rows, int(counts[0]), int(counts[1]), tol, du, dv,
                                "u" in closed, "v" in closed, parameters, threads)
