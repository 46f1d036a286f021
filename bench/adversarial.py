#!/usr/bin/python3
"""Inputs nobody tuned for: generated cases the CLI's default must survive, checked independently
(the results: docs/adversarial.md).

Each case is made here from a formula and a seeded random generator, of kinds that
bench/scan_cases.py does not make: rows in reverse or alternating order, repeated points,
identical rows, a row of 2 points, a very long row beside short ones, a closed contour with
a spike, zigzag rows, a near-planar set, a vertical wall, a 10^5-point DEM with a cliff,
offsets of 1e7, tolerances of 1e-7 and 1e-9 of the diagonal, a per-axis tolerance with one
axis 0, NaN and infinity, blank lines between rows, CRLF, 20,000 tiny rows, and bad files.

Each case runs `CLI fit CASE.rows` (default method, a timeout) and is checked:
- exit code: 0 for data that can be fitted; for a bad input a documented input code
  (2 ... 5, never 8) with exactly one line on standard error naming file:line or the option,
  and no output written (an existing file at an output path left untouched);
- every output written (JSON, report, and where cheap STL, OBJ, STEP);
- T at every point, by this script's own evaluation of the written JSON surface (the
  textbook Cox-de Boor formula on the stored knots and control points, docs/surface-json.md):
  for each data point the surface point that uses the least of its per-axis tolerance (a
  closest point in the tolerance-scaled metric: seeds from a dense sample of the surface, then
  Gauss-Newton, then a minimax polish of the points that still look outside); a point holds
  when max over the axes of |S - D| / T is at most 1 (plus a few ulps of its coordinates); an
  axis with T = 0 gets the round-off allowance of docs/method.md section 6 (1e-10 of the
  diagonal);
- control points (nu x nv, distinct) at most the points, unless the report says that T forces
  interpolation;
- the report's fold measure is 0, its `within_tolerance` true;
- the run's wall time (flagged "slow" above --slow seconds, "hang" at the timeout).

    bench/adversarial.py build/apps/sfit/sfit [--seed N] [--only NAME] [--timeout S] [--slow S]
                         [--keep DIR]

Prints one line per case and then the table of failures (empty: every check held).
"""

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time

import numpy as np
from scipy.spatial import cKDTree

from adversarial_cases import CASES, CHEAP_POINTS, rows_text


# ----------------------------------------------------------------------------- checker

def basis(knots, p, t):
    """Spans and the p + 1 non-zero B-spline values at each t (The NURBS Book, A2.1, A2.2)."""
    n = len(knots) - p - 1
    span = np.clip(np.searchsorted(knots, t, side="right") - 1, p, n - 1)
    N = np.zeros((len(t), p + 1))
    N[:, 0] = 1.0
    left = np.zeros((len(t), p + 1))
    right = np.zeros((len(t), p + 1))
    for j in range(1, p + 1):
        left[:, j] = t - knots[span + 1 - j]
        right[:, j] = knots[span + j] - t
        saved = np.zeros(len(t))
        for r in range(j):
            den = right[:, r + 1] + left[:, j - r]
            temp = np.divide(N[:, r], den, out=np.zeros(len(t)), where=den != 0)
            N[:, r] = saved + right[:, r + 1] * temp
            saved = left[:, j - r] * temp
        N[:, j] = saved
    return span, N


class Surface:
    def __init__(self, js, centre):
        self.p, self.q = js["degree"]
        self.ku = np.array(js["knots_u"], float)
        self.kv = np.array(js["knots_v"], float)
        self.P = np.array(js["control_points"], float) - centre  # nu x nv x 3
        self.periodic = js.get("periodic", [False, False])
        nu, nv = self.P.shape[:2]
        self.dom = [(self.ku[self.p], self.ku[nu]), (self.kv[self.q], self.kv[nv])]

    def fix(self, u, v):
        out = []
        for t, (a, b), per in zip((u, v), self.dom, self.periodic):
            t = (a + np.mod(t - a, b - a)) if per else np.clip(t, a, b)
            out.append(t)
        return out

    def __call__(self, u, v):
        u, v = self.fix(u, v)
        su, Nu = basis(self.ku, self.p, u)
        sv, Nv = basis(self.kv, self.q, v)
        S = np.zeros((len(u), 3))
        for i in range(self.p + 1):
            for j in range(self.q + 1):
                S += (Nu[:, i] * Nv[:, j])[:, None] * self.P[su - self.p + i, sv - self.q + j]
        return S


def check_points(js, pts, T, diag):
    """Number of points farther than T on some axis from every point of the surface, and the
    largest max_a |S - D|_a / T_a found (a ratio: at most 1 holds)."""
    centre = 0.5 * (pts.min(0) + pts.max(0))
    D = pts - centre
    S = Surface(js, centre)
    Teff = np.where(np.asarray(T) > 0, T, 1e-10 * diag)
    # a few ulps of the coordinates as written: the JSON's doubles are the surface
    slack = 8 * np.finfo(float).eps * (np.abs(pts).max(0) + np.abs(np.array(
        js["control_points"], float)).reshape(-1, 3).max(0))
    Tchk = Teff + slack
    nu, nv = S.P.shape[:2]
    mu = int(min(max(6 * nu, 60), 1500))
    mv = int(min(max(6 * nv, 60), 1500))
    while mu * mv > 2_000_000:
        mu, mv = int(mu * 0.8), int(mv * 0.8)
    gu = np.linspace(*S.dom[0], mu)
    gv = np.linspace(*S.dom[1], mv)
    UU, VV = np.meshgrid(gu, gv, indexing="ij")
    UU, VV = UU.ravel(), VV.ravel()
    samp = S(UU, VV)
    hu = 1e-7 * (S.dom[0][1] - S.dom[0][0])
    hv = 1e-7 * (S.dom[1][1] - S.dom[1][0])

    def closest(M):
        """Closest points in the metric |x / M|: a sample's seed, then Gauss-Newton."""
        _, idx = cKDTree(samp / M).query(D / M)
        u, v = UU[idx].copy(), VV[idx].copy()
        for _ in range(12):
            R = (S(u, v) - D) / M
            Ju = (S(u + hu, v) - S(u - hu, v)) / (2 * hu) / M
            Jv = (S(u, v + hv) - S(u, v - hv)) / (2 * hv) / M
            a, b, c = (Ju * Ju).sum(1), (Ju * Jv).sum(1), (Jv * Jv).sum(1)
            gu_, gv_ = (Ju * R).sum(1), (Jv * R).sum(1)
            det = a * c - b * b
            ok = np.abs(det) > 1e-300
            du = np.where(ok, -(c * gu_ - b * gv_) / np.where(ok, det, 1), 0)
            dv = np.where(ok, -(a * gv_ - b * gu_) / np.where(ok, det, 1), 0)
            nu_, nv_ = S.fix(u + du, v + dv)
            better = (np.square((S(nu_, nv_) - D) / M).sum(1) < np.square(R).sum(1))
            u, v = np.where(better, nu_, u), np.where(better, nv_, v)
        return u, v, (np.abs(S(u, v) - D) / Tchk).max(1)

    # two metrics: the tolerance's (its anisotropy capped at 1e3: an axis with T = 0 would
    # make the system singular) and the plain Euclidean one; each point keeps the better
    u, v, ratio = closest(np.maximum(Teff, 1e-3 * Teff.max()))
    if Teff.max() > Teff.min():
        u2, v2, r2 = closest(np.full(3, Teff.max()))
        take = r2 < ratio
        u, v, ratio = np.where(take, u2, u), np.where(take, v2, v), np.minimum(r2, ratio)
    bad = np.nonzero(ratio > 1)[0]
    # Minimax polish of what still looks outside: the closest point in the scaled Euclidean
    # metric can use up to sqrt(3) times the per-axis ratio's minimum, so each such point
    # searches a shrinking 41 x 41 window around it for the least max_a |S - D|_a / T_a.
    su, sv = (S.dom[0][1] - S.dom[0][0]) / mu, (S.dom[1][1] - S.dom[1][0]) / mv
    w = np.linspace(-1, 1, 41)
    WU, WV = np.meshgrid(w, w, indexing="ij")
    WU, WV = WU.ravel(), WV.ravel()
    for k in bad[:2000]:
        bu, bv, best = u[k], v[k], ratio[k]
        ru, rv = 4 * su, 4 * sv
        for _ in range(24):
            cu, cv = bu + ru * WU, bv + rv * WV
            r = (np.abs(S(cu, cv) - D[k]) / Tchk).max(1)
            j = int(np.argmin(r))
            if r[j] < best:
                best = r[j]
                bu, bv = S.fix(np.array([cu[j]]), np.array([cv[j]]))
                bu, bv = bu[0], bv[0]
            ru, rv = ru / 3, rv / 3
        ratio[k] = best
    return int((ratio > 1).sum()), float(ratio.max())


# ----------------------------------------------------------------------------- runner

def run_case(cli, name, make, opts, expect, tweak, seed, tmp, timeout, formats):
    rows = make(np.random.default_rng(seed))
    text = rows_text(rows)
    if tweak:
        text = tweak(text)
    path = os.path.join(tmp, name + ".rows")
    with open(path, "w", newline="") as f:
        f.write(text)
    pts = np.concatenate(rows)
    npts = len(pts)
    outs = [os.path.join(tmp, name + ".json"), os.path.join(tmp, name + ".report.json")]
    extra = []
    if expect == "fit" and npts <= CHEAP_POINTS:
        big = np.abs(pts).max() > 1e6  # STL's float32 is refused there (docs/errors.md, 6)
        for ext in (("obj",) if big else ("stl", "obj")) + (("step",) if "step" in formats else ()):
            extra.append(os.path.join(tmp, name + "." + ext))
    for o in outs + [os.path.join(tmp, name + "." + e) for e in ("stl", "obj", "step")]:
        if os.path.exists(o):  # a run before in a kept folder: its files are not this run's
            os.remove(o)
    sentinel = b"existing file, must stay\n"
    if expect == "input":  # an existing file at every output path must stay untouched
        for o in outs:
            with open(o, "wb") as f:
                f.write(sentinel)
    cmd = [cli, "fit", path, "-q", "-o", outs[0], "--report", outs[1]] + \
        sum((["-o", e] for e in extra), []) + opts
    res = {"case": name, "points": npts, "rows": len(rows), "fails": []}
    t0 = time.time()
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        res["seconds"] = time.time() - t0
        res["fails"].append(f"hang: no exit within {timeout} s")
        return res
    res["seconds"] = time.time() - t0
    res["exit"] = p.returncode
    err = p.stderr.strip()
    if expect == "input":
        lines = err.splitlines()
        if p.returncode not in (2, 3, 4, 5):
            res["fails"].append(f"exit {p.returncode} on a bad input (want 2...5): {err[:120]}")
        if len(lines) != 1:
            res["fails"].append(f"{len(lines)} lines on stderr, want 1")
        elif not (name + ".rows:" in lines[0]):
            res["fails"].append(f"the line names no file:line: {lines[0][:120]}")
        for o in outs:
            if open(o, "rb").read() != sentinel:
                res["fails"].append(f"{os.path.basename(o)} replaced by a failed run")
        left = [f for f in os.listdir(tmp) if ".sfit-" in f]
        if left:
            res["fails"].append(f"temporaries left: {left}")
        res["note"] = lines[0][:90] if lines else ""
        return res
    if p.returncode != 0:
        res["fails"].append(f"exit {p.returncode}: {err[:160]}")
        written = [o for o in outs + extra if os.path.exists(o)]
        if written:
            res["fails"].append(f"a failed run wrote {written}")
        return res
    missing = [os.path.basename(o) for o in outs + extra
               if not os.path.exists(o) or os.path.getsize(o) == 0]
    if missing:
        res["fails"].append(f"outputs missing: {missing}")
        return res
    js = json.load(open(outs[0]))
    rep = json.load(open(outs[1]))
    cp = rep["control_points"]
    res["nu"], res["nv"] = cp
    res["rule"] = rep.get("parameters", "")
    res["fold"] = rep.get("fold", 0.0)
    forced = "forces interpolation" in rep.get("stop_reason", "")
    res["forced"] = forced
    if not rep.get("within_tolerance", False):
        res["fails"].append("report: within_tolerance false at exit 0")
    if cp[0] * cp[1] > npts and not forced:
        res["fails"].append(f"{cp[0]} x {cp[1]} = {cp[0] * cp[1]} control points > {npts} "
                            "points, and the report does not say T forces interpolation")
    if res["fold"] > 0:
        res["fails"].append(f"fold {res['fold']:.3g}")
    diag = float(np.linalg.norm(pts.max(0) - pts.min(0)))
    T = np.array(rep["tolerance"], float)
    nbad, worst = check_points(js, pts, T, diag)
    res["outside"], res["worst"] = nbad, worst
    if nbad:
        res["fails"].append(f"{nbad} points outside T by the independent check "
                            f"(worst {worst:.3g} T), report says within")
    return res


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("cli")
    ap.add_argument("--seed", type=int, default=11)
    ap.add_argument("--only", default="")
    ap.add_argument("--timeout", type=float, default=120)
    ap.add_argument("--keep", default="", help="run in this folder and keep its files")
    ap.add_argument("--slow", type=float, default=30,
                    help="a whole run longer than this many seconds is a failure (slow)")
    a = ap.parse_args()
    fm = subprocess.run([a.cli, "formats"], capture_output=True, text=True).stdout.lower()
    formats = "step" if ("step" in fm and "no module" not in fm) else ""
    print(f"{'case':<20} {'points':>7} {'exit':>4} {'nu x nv':>11} {'cp/pts':>6} "
          f"{'rule':>11} {'fold':>7} {'worst/T':>7} {'s':>6}  note")
    failures = []
    with tempfile.TemporaryDirectory() as tmp:
        tmp = a.keep or tmp
        for name, (make, opts, expect, tweak) in CASES.items():
            if a.only and a.only not in name:
                continue
            r = run_case(a.cli, name, make, opts, expect, tweak, a.seed, tmp, a.timeout, formats)
            if r["seconds"] > a.slow and not any(f.startswith("hang") for f in r["fails"]):
                r["fails"].append(f"slow: {r['seconds']:.1f} s")
            cps = f"{r['nu']:>5} x {r['nv']:<5}" if "nu" in r else f"{'-':>11}"
            ratio = f"{r['nu'] * r['nv'] / r['points']:>6.3f}" if "nu" in r else f"{'-':>6}"
            note = r.get("note", "") or ("T forces interpolation" if r.get("forced") else "")
            print(f"{name:<20} {r['points']:>7} {r.get('exit', '-')!s:>4} {cps} {ratio} "
                  f"{r.get('rule', '-'):>11} {r.get('fold', 0):>7.2g} "
                  f"{r.get('worst', 0):>7.3f} {r['seconds']:>6.2f}  {note}")
            sys.stdout.flush()
            for f in r["fails"]:
                failures.append((name, f))
    print(f"\n{len(failures)} failures")
    if failures:
        print(f"{'case':<20} failure")
        for name, f in failures:
            print(f"{name:<20} {f}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
