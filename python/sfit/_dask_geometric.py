"""sfit.dask.fit(parameters="geometric") (docs/python.md, "More than one machine"): the
library's geometric rule (each point's (u, v) from its projection onto a base plane, corrected
by projection onto the fit; the scattered least squares with a small smoothness term) split
into what a worker computes from its chunk and what the client computes from sums.

Passes over the points (each chunk read by its worker):
  sums       the points' number and sum, the rows' directions (last point - first point),
             the first and last rows' edge sums (their edge centroids orient v)
  scatter    sum (d - c)(d - c)^T about the mean c: the client finds the plane (the library's
             sheet_frame())
  positions  each point's position along and across the plane; min/max reduced; the
             fractions (u, v in [0, 1]) made from them stay on the workers (persisted)
  per round  the scattered normal equations at (nu, nv) (band + right-hand sides, summed by
             Dask's tree reduction), solved on the client with the smoothness term at both
             weights the library may use, then one check of both (max-reduced with the knot
             spans the points cover)
  correction each point's (u, v) moved to its closest point on the fit, on its worker.
Only sums, the control points and the verdicts travel; the per-point parameters never do.
"""

import time

import numpy as np

from . import _sfit
from ._dask_input import _error, _given_counts

_RULES = None


def rules():
    """The library's constants of the rule (smoothing, its lowering, correction rounds)."""
    global _RULES
    if _RULES is None:
        _RULES = dict(_sfit._geometric_rules())
    return _RULES


# ---------------------------------------------------------------------------- worker tasks

def _runs(chunk):
    """The chunk's runs of one row: (a, b, row, k0 = index of the run's first point in its row,
    the row's size)."""
    g0, r0, starts, sizes, _ = chunk.info
    r = chunk.block[:, 3].astype(np.int64)
    first = np.flatnonzero(np.diff(r, prepend=-1))
    ends = np.append(first[1:], len(r))
    for a, b in zip(first, ends):
        j = int(r[a]) - r0
        yield int(a), int(b), int(r[a]), int(g0 + a - starts[j]), int(sizes[j])


def _sums(chunk, centre):
    """n, sum of d, the rows' directions, and for the first and last rows each run's edge
    sums with its end points (d: the points less the centre)."""
    d = chunk.block[:, :3] - centre
    M = chunk.info[4]
    along = np.zeros(3)
    ends = []
    for a, b, row, k0, size in _runs(chunk):
        if size >= 2:
            if k0 == 0:
                along -= d[a]
            if k0 + (b - a) == size:
                along += d[b - 1]
        if row in (0, M - 1):
            p = d[a:b]
            lens = np.linalg.norm(np.diff(p, axis=0), axis=1)
            esum = (0.5 * lens[:, None] * (p[:-1] + p[1:])).sum(axis=0)
            ends.append((row, k0, esum, float(lens.sum()), p.sum(axis=0), b - a,
                         p[0].copy(), p[-1].copy()))
    return len(d), d.sum(axis=0), along, ends


def _scatter(chunk, centre, mean):
    e = chunk.block[:, :3] - centre - mean
    return e.T @ e


def _positions(chunk, centre, frame):
    return _sfit._sheet_positions(chunk.block, centre, frame)


def _range(pos):
    return np.concatenate([pos.min(axis=0), -pos.max(axis=0)])


def _fractions(pos, lo, span):
    """As the library's scale_to_unit(): (t - min) / (max - min) clamped to [0, 1], 0 where
    the span is 0."""
    out = np.zeros_like(pos)
    for a in range(2):
        if span[a] > 0:
            out[:, a] = np.clip((pos[:, a] - lo[a]) / span[a], 0.0, 1.0)
    return out


def _partial(chunk, centre, fuv, nu, nv, spec):
    return _sfit._geometric_partial(chunk.block, centre, fuv, nu, nv, *spec)


def _check(chunk, centre, fuv, controls, spec, tol, roundoff):
    return np.concatenate([_sfit._geometric_check(chunk.block, centre, fuv, c, *spec, tol,
                                                  roundoff) for c in controls])


def _project(chunk, centre, fuv, control, spec):
    return _sfit._geometric_project(chunk.block, centre, fuv, control, *spec)


# ---------------------------------------------------------------------------- the client

def _edge_centroid(ends):
    """The edge centroid of one row from its runs over the chunks (the library's
    edge_centroid(), open): the edges inside each run plus those joining consecutive runs."""
    ends = sorted(ends, key=lambda e: e[1])
    esum, total = np.zeros(3), 0.0
    psum, count = np.zeros(3), 0
    for i, (_, k0, es, tl, ps, n, first, last) in enumerate(ends):
        esum, total, psum, count = esum + es, total + tl, psum + ps, count + n
        if i + 1 < len(ends):
            nxt = ends[i + 1][6]
            length = float(np.linalg.norm(nxt - last))
            esum, total = esum + 0.5 * length * (last + nxt), total + length
    return esum / total if total > 0 else psum / max(1, count)


class GeometricRunner:
    """The distributed geometric rule over `chunks` (delayed _Chunk objects) for one fit."""

    def __init__(self, run, chunks, centre, box_min, box_max, T, roundoff, spec, split_every,
                 max_result_bytes):
        self.run, self.chunks, self.centre = run, chunks, centre
        self.box_min, self.box_max, self.T, self.roundoff = box_min, box_max, T, roundoff
        self.spec, self.split_every, self.max_bytes = spec, split_every, max_result_bytes
        self.pairs = []

    def _reduce(self, what, tasks, size, how):
        import dask.array as da

        parts = [da.from_delayed(t, shape=size, dtype=float) for t in tasks]
        stacked = da.stack(parts)
        total = getattr(stacked, how)(axis=0, split_every=self.split_every)
        (out,) = self.run(what, 1, total)
        return out

    def base_fractions(self):
        """The base plane's fractions of every point, persisted on the workers (one list entry
        per chunk), or None where the points span no plane."""
        import dask

        D = dask.delayed
        sums = self.run("geometric sums", 1,
                        *[D(_sums, pure=True)(c, self.centre) for c in self.chunks])
        n = sum(s[0] for s in sums)
        mean = sum((s[1] for s in sums), np.zeros(3)) / n
        along = sum((s[2] for s in sums), np.zeros(3))
        ends = [e for s in sums for e in s[3]]
        M = max(e[0] for e in ends) + 1
        first = _edge_centroid([e for e in ends if e[0] == 0])
        last = _edge_centroid([e for e in ends if e[0] == M - 1])
        cov = self._reduce("geometric scatter",
                           [D(_scatter, pure=True)(c, self.centre, mean) for c in self.chunks],
                           (3, 3), "sum")
        frame = _sfit._sheet_frame(mean, cov, along, first, last)
        if frame is None:
            return None
        pos = self.run.persist("positions on the base plane", 1,
                               *[D(_positions, pure=True)(c, self.centre, frame)
                                 for c in self.chunks])
        r = self._reduce("positions' range", [D(_range, pure=True)(p) for p in pos], (4,), "min")
        lo, hi = r[:2], -r[2:]
        states = list(self.run.persist("base fractions", 1,
                                       *[D(_fractions, pure=True)(p, lo, hi - lo)
                                         for p in pos]))
        return states

    def normal_equations(self, states, nu, nv):
        import dask

        size = _sfit._geometric_partial_size(nu, nv, self.spec[0], self.spec[1])
        if 8 * size > self.max_bytes:
            raise _error("usage", f"{nu} x {nv} control points: one chunk's normal equations "
                         f"would be {8 * size / 2**20:.0f} MiB, above the 256 MiB a task may "
                         "return", option="counts")
        return self._reduce(f"geometric normal equations {nu} x {nv}",
                            [dask.delayed(_partial, pure=True)(c, self.centre, s, nu, nv,
                                                               self.spec)
                             for c, s in zip(self.chunks, states)], (size,), "sum")

    def check(self, states, controls):
        """One pass: every chunk checks its points against each surface of `controls` (the
        same counts) and returns, per surface, [not within, not near, worst ratio, max |S - D|
        per axis, covered knot spans]; max-reduced."""
        import dask

        nu, nv = controls[0].shape[:2]
        du, dv, cu, cv = self.spec
        size = 6 + (nu if cu else nu - du) * (nv if cv else nv - dv)
        nbytes = sum(c.nbytes for c in controls)
        c = dask.delayed(controls, pure=True) if nbytes > (1 << 20) else controls
        out = self._reduce(f"check {nu} x {nv}",
                           [dask.delayed(_check, pure=True)(ch, self.centre, s, c, self.spec,
                                                            self.T, self.roundoff)
                            for ch, s in zip(self.chunks, states)], (size * len(controls),),
                           "max")
        return [out[k * size:(k + 1) * size] for k in range(len(controls))]

    def attempt(self, states, nu, nv):
        """The library's attempt() at (nu, nv): the smoothness weight from its default,
        lowered (once) where T was missed by at most smoothing_reach; holds: every point within
        T (per axis and the ellipsoid), the surface near the data where covered and calm
        elsewhere, and no fold. One pass of normal equations (they do not depend on the
        weight); the surfaces of both weights solved here and checked in one pass (the second
        is used only where the library would make it)."""
        R = rules()
        flat = self.normal_equations(states, nu, nv)
        weights, controls = [], []
        w = R["smoothing"]
        while w >= R["smoothing"] * R["smoothing_lower"]:
            control = _sfit._geometric_solve(flat, nu, nv, w, *self.spec)
            if control is None:
                break
            weights.append(w)
            controls.append(control)
            w *= R["smoothing_lower"]
        if not controls:
            return None
        checks = self.check(states, controls)
        a = None
        for w, control, out in zip(weights, controls, checks):
            holds = out[0] == 0 and out[1] == 0
            guard = None
            if holds:
                near, fold, folds = _sfit._geometric_guards(control, out[6:], *self.spec,
                                                            self.box_min, self.box_max)
                guard = None if near else "far from the data"
                guard = "fold" if near and folds else guard
            a = {"holds": bool(holds and guard is None), "ratio": float(out[2]),
                 "control": control, "dev": out[3:6].copy(), "smoothing": w, "guard": guard}
            self.pairs.append({"counts": [nu, nv], "holds": a["holds"], "rows_step": 1,
                               "max_deviation": a["dev"].tolist(), "guard": guard,
                               "smoothing": w})
            if holds and guard != "far from the data":  # held, or failed only by a fold
                return a
            if a["ratio"] > R["smoothing_reach"] and w <= R["smoothing"]:
                return a
        return a

    def at_counts(self, base, nu, nv):
        """The library's geometric_at_counts(): the surface at the base fractions, then rounds
        of correction (project every point onto the fit, refit) while it misses T and its
        worst deviation falls. Returns (attempt or None, corrections)."""
        import dask

        at = self.attempt(base, nu, nv)
        if at is None:
            return None, 0
        states, rounds = base, 0
        for _ in range(rules()["correction_rounds"]):
            if at["holds"]:
                break
            nxt = list(self.run.persist(
                f"correction {nu} x {nv}", 1,
                *[dask.delayed(_project, pure=True)(c, self.centre, s, at["control"], self.spec)
                  for c, s in zip(self.chunks, states)]))
            a = self.attempt(nxt, nu, nv)
            if a is None or not (a["holds"] or a["ratio"] < at["ratio"]):
                break
            at, states, rounds = a, nxt, rounds + 1
        return at, rounds


def fit_geometric(runner, counts, n_points, M, longest):
    """The fit at `counts`, or the count search (gallop both counts up until a pair holds, then
    bisect nu, then nv, each probe the rule at those counts). Returns (control centred, report
    entries, pairs)."""
    du, dv = runner.spec[0], runner.spec[1]
    base = runner.base_fractions()
    if base is None:
        raise _error("input-data", "parameters geometric: the points span no plane")
    results = {}

    def probe(nu, nv):
        if (nu, nv) not in results:
            results[(nu, nv)] = runner.at_counts(base, nu, nv)
        at = results[(nu, nv)][0]
        return at is not None and at["holds"]

    stop = "counts given"
    if counts is not None:
        nu, nv = _given_counts(counts, du, dv)
        probe(nu, nv)
    else:
        most = max(longest, M)
        top = min(rules()["max_unknowns"], n_points)
        nu, nv = min(most, 2 * (du + 1)), min(most, 2 * (dv + 1))
        while not probe(nu, nv):
            nu2, nv2 = min(most, 2 * nu), min(most, 2 * nv)
            if (nu2, nv2) == (nu, nv) or nu2 * nv2 > top:
                raise _error("tolerance-not-met", f"parameters geometric: no surface within T "
                             f"up to {nu} x {nv} control points")
            nu, nv = nu2, nv2
        lo, hi = du, nu
        while hi - lo > 1:
            mid = (lo + hi) // 2
            lo, hi = (lo, mid) if probe(mid, nv) else (mid, hi)
        nu = hi
        lo, hi = dv, nv
        while hi - lo > 1:
            mid = (lo + hi) // 2
            lo, hi = (lo, mid) if probe(nu, mid) else (mid, hi)
        nv = hi
        stop = "minimal (gallop, then bisection of each count)"
    at, rounds = results[(nu, nv)]
    if at is None:
        raise _error("tolerance-not-met", f"no surface with {nu} x {nv} control points at "
                     "parameters geometric", option="counts")
    if rounds:
        stop += f"; parameters corrected {rounds} time" + ("s" if rounds > 1 else "")
    report = {"max_deviation": at["dev"].tolist(), "within_tolerance": at["holds"],
              "control_points": [nu, nv], "stop_reason": stop, "corrections": rounds,
              "smoothing": at["smoothing"], "guard": at["guard"],
              "partial_bytes": 8 * _sfit._geometric_partial_size(nu, nv, du, dv)}
    return at["control"], report, runner.pairs


def fit_after_statistics(run, work, centre, box_min, box_max, T, roundoff, du, dv, split_every,
                         counts, n_points, M, row_sizes, t0):
    """sfit.dask.fit() at parameters "geometric" after its statistics' pass: no sample of rows
    (the search probes every point); the per-point parameters stay on the workers."""
    import dask

    from ._dask_tasks import _rows_sample
    from .dask import MAX_RESULT_BYTES, DaskFit

    chunks = [dask.delayed(_rows_sample, pure=True)(b, info, 1) for b, info in work]
    runner = GeometricRunner(run, chunks, centre, box_min, box_max, T, roundoff,
                             (du, dv, False, False), split_every, MAX_RESULT_BYTES)
    control, entries, pairs = fit_geometric(runner, counts, n_points, M,
                                            int(row_sizes.max()))
    surface = _sfit._surface_from_control(control, du, dv, False, False, centre)
    report = {
        "points": n_points, "rows": M, "tolerance": T.tolist(), "degree": [du, dv],
        "closed": [False, False], "parametrization": "geometric",
        "method": "dask least squares (scattered, smoothness term)", "pairs_tried": len(pairs),
        "chunks": len(work), "rows_step": 1,
        "full_passes": sum(p["rows_step"] == 1 for p in run.log), "passes": run.log,
        "roundoff": roundoff, "seconds": time.perf_counter() - t0, **entries}
    return DaskFit(surface, report, None, row_sizes, pairs)
