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
import math
import os
import subprocess
import sys
import tempfile
import time

import numpy as np
from scipy.spatial import cKDTree


# ----------------------------------------------------------------------------- data

def field(x, y):
    return (0.35 * np.exp(-((x - 0.3) ** 2 + (y + 0.2) ** 2) / 0.18)
            - 0.25 * np.exp(-((x + 0.4) ** 2 + (y - 0.35) ** 2) / 0.09)
            + 0.08 * np.sin(2.5 * x + 1.3 * y))


def grid(nx, ny, f=field, jitter=0.0, rng=None):
    rows = []
    xs = np.linspace(-1, 1, nx)
    for y in np.linspace(-1, 1, ny):
        x = xs + (rng.uniform(-jitter, jitter, nx) if jitter else 0)
        rows.append(np.column_stack([x, np.full(nx, y), f(x, np.full(nx, y))]))
    return rows


def reversed_rows(rng):
    """A smooth 60 x 50 grid, rows given last to first."""
    return grid(60, 50, rng=rng)[::-1]


def alternating_rows(rng):
    """A smooth 60 x 50 grid scanned back and forth (every other row reversed)."""
    return [r if k % 2 == 0 else r[::-1] for k, r in enumerate(grid(60, 50, rng=rng))]


def duplicated_points(rng):
    """A 50 x 40 grid where about a fifth of the points are repeated right after themselves."""
    out = []
    for r in grid(50, 40, rng=rng):
        rep = np.where(rng.uniform(size=len(r)) < 0.2, 2, 1)
        out.append(np.repeat(r, rep, axis=0))
    return out


def identical_rows(rng):
    """A 50 x 40 grid where row 20 is given twice in a row (the same points)."""
    g = grid(50, 40, rng=rng)
    return g[:21] + [g[20].copy()] + g[21:]


def two_point_row(rng):
    """A 50 x 40 grid where one row in the middle keeps only its two end points."""
    g = grid(50, 40, rng=rng)
    g[17] = g[17][[0, -1]]
    return g


def long_beside_short(rng):
    """30 rows of 5 points beside one row of 3000 points, all on one smooth surface."""
    rows = []
    for k, y in enumerate(np.linspace(-1, 1, 31)):
        n = 3000 if k == 15 else 5
        x = np.linspace(-1, 1, n)
        rows.append(np.column_stack([x, np.full(n, y), field(x, np.full(n, y))]))
    return rows


def spiked_contour(rng):
    """20 closed sections of a tube (80 points each); section 9 has a spike of 0.3 at one point."""
    rows = []
    for k, zc in enumerate(np.linspace(0, 2, 20)):
        a = np.linspace(0, 2 * math.pi, 80, endpoint=False)
        r = 1 + 0.1 * np.cos(2 * a) + 0.05 * zc
        if k == 9:
            r = r.copy()
            r[23] += 0.3
        rows.append(np.column_stack([r * np.cos(a), r * np.sin(a), np.full(80, zc)]))
    return rows


def zigzag_rows(rng):
    """40 rows, each a zigzag across a band of the surface: x runs on, y jumps back and forth."""
    rows = []
    for y0 in np.linspace(-0.95, 0.95, 40):
        x = np.linspace(-1, 1, 80)
        y = y0 + 0.02 * np.where(np.arange(80) % 2 == 0, 1.0, -1.0)
        rows.append(np.column_stack([x, y, field(x, y)]))
    return rows


def near_planar(rng):
    """A 40 x 40 grid of the plane z = 0.1 x + 0.2 y with noise of 1e-9."""
    return grid(40, 40, lambda x, y: 0.1 * x + 0.2 * y + rng.normal(0, 1e-9, x.shape), rng=rng)


def vertical_wall(rng):
    """A wall: 40 rows stacked in z, each a horizontal line along x with a small wave in y."""
    rows = []
    for z in np.linspace(0, 3, 40):
        x = np.linspace(-2, 2, 70)
        rows.append(np.column_stack([x, 0.1 * np.sin(2 * x + z), np.full(70, z)]))
    return rows


def dem_cliff(rng):
    """A 330 x 310 DEM (102,300 points) with a cliff: a step of 0.3 across a band 0.01 wide."""
    def f(x, y):
        return field(x, y) + 0.3 * 0.5 * (1 + np.tanh((x - 0.2 * y) / 0.005))
    return grid(330, 310, f, rng=rng)


def offset_1e7(rng):
    """A 80 x 60 terrain of 2 km x 2 km (heights in m), moved by 1e7 on x, y and z."""
    return [r * np.array([1000.0, 1000.0, 100.0]) + 1e7 for r in grid(80, 60, rng=rng)]


def smooth_small(rng):
    """A 30 x 25 smooth grid with a little jitter along x."""
    return grid(30, 25, jitter=0.01, rng=rng)


def tiny_rows(rng, count):
    """`count` rows of 2 or 3 points each across the smooth field."""
    rows = []
    for y in np.linspace(-1, 1, count):
        n = int(rng.integers(2, 4))
        x = np.sort(rng.uniform(-1, 1, n))
        rows.append(np.column_stack([x, np.full(n, y), field(x, np.full(n, y))]))
    return rows


def many_tiny_rows(rng):
    """20,000 rows of 2 or 3 points each across a smooth surface (50,000 points)."""
    return tiny_rows(rng, 20000)


def middle_pole(rng):
    """Closed sections of a vase pinched to one point (a pole) in the middle of the rows."""
    rows = []
    for zc in np.linspace(-1, 1, 21):
        if abs(zc) < 1e-12:
            rows.append(np.array([[0.0, 0.0, 0.0]]))
            continue
        a = np.linspace(0, 2 * math.pi, 60, endpoint=False)
        r = abs(zc) * (1 + 0.1 * np.cos(3 * a))
        rows.append(np.column_stack([r * np.cos(a), r * np.sin(a), np.full(60, zc)]))
    return rows


def two_point_rows(rng, height):
    """60 rows of 2 points each (fewer than degree + 1) near x = -1 and 1, z = height(x, y)."""
    rows = []
    for y in np.linspace(-1, 1, 60):
        x = np.array([-1.0, 1.0]) + rng.uniform(-0.05, 0.05, 2)
        rows.append(np.column_stack([x, np.full(2, y), height(x, np.full(2, y))]))
    return rows


def all_two_point_rows(rng):
    """60 rows of 2 points each across the smooth field: a ruled surface."""
    return two_point_rows(rng, field)


def two_point_rows_wave(rng):
    """60 rows of 2 points each across the sheet z = 0.3 sin(2x + y) + 0.2 cos(3y)."""
    return two_point_rows(rng, lambda x, y: 0.3 * np.sin(2 * x + y) + 0.2 * np.cos(3 * y))


def mixed_closed(rng):
    """30 closed sections of a tube, each starting at a random point, every third reversed."""
    rows = []
    for k, zc in enumerate(np.linspace(0, 3, 30)):
        n = int(rng.integers(50, 90))
        a = np.linspace(0, 2 * math.pi, n, endpoint=False) + rng.uniform(0, 2 * math.pi)
        r = 1 + 0.2 * np.cos(3 * a) + 0.1 * math.sin(zc)
        p = np.column_stack([r * np.cos(a), 0.7 * r * np.sin(a), np.full(n, zc)])
        rows.append(p[::-1] if k % 3 == 0 else p)
    return rows


def tiny_rows_1e5(rng):
    """50,000 rows of 2 or 3 points (about 10^5 points)."""
    return tiny_rows(rng, 50000)


def one_row(rng):
    return grid(40, 1, rng=rng)


def offset_1e8(rng):
    """The 80 x 60 terrain of 2 km moved by 1e8 on x, y and z."""
    return [r * np.array([1000.0, 1000.0, 100.0]) + 1e8 for r in grid(80, 60, rng=rng)]


def ragged_uneven(rng):
    """300 rows of 20 ... 400 points, each row crowded in its own place, each clipped to its
    own part of [-1, 1] (a random start and end)."""
    rows = []
    for y in np.linspace(-1, 1, 300):
        n = int(rng.integers(20, 401))
        a, b = np.sort(rng.uniform(-1, 1, 2))
        if b - a < 0.2:
            a, b = a - 0.1, b + 0.1
        t = np.sort(rng.uniform(0, 1, n)) ** rng.uniform(0.5, 2)
        x = a + (b - a) * t
        rows.append(np.column_stack([x, np.full(n, y), field(x, np.full(n, y))]))
    return rows


# ----------------------------------------------------------------------------- cases
# name: (make rows, CLI options, expected: "fit" or "input", text tweak of the file or None)

def empty(text):
    return ""


def comments_only(text):
    return "# nothing but a comment\n\n# and another\n"


def crlf(text):
    return text.replace("\n", "\r\n")


def blank_lines(text):
    return text.replace("\n\n", "\n\n   \n\t\n# between rows\n\n")


def put_nan(text):
    lines = text.split("\n")
    lines[57] = "0.5 nan 0.25"
    return "\n".join(lines)


def put_inf(text):
    lines = text.split("\n")
    lines[123] = "0.5 0.1 -inf"
    return "\n".join(lines)


def two_numbers(text):
    lines = text.split("\n")
    lines[40] = "0.5 0.25"
    return "\n".join(lines)


def huge_number(text):
    lines = text.split("\n")
    lines[12] = "1e400 0 0"
    return "\n".join(lines)


CASES = {
    "reversed_rows": (reversed_rows, [], "fit", None),
    "alternating_rows": (alternating_rows, [], "fit", None),
    "duplicated_points": (duplicated_points, [], "fit", None),
    "identical_rows": (identical_rows, [], "fit", None),
    "two_point_row": (two_point_row, [], "fit", None),
    "long_beside_short": (long_beside_short, [], "fit", None),
    "spiked_contour": (spiked_contour, ["--closed", "u"], "fit", None),
    "zigzag_rows": (zigzag_rows, [], "fit", None),
    "near_planar": (near_planar, [], "fit", None),
    "vertical_wall": (vertical_wall, [], "fit", None),
    "dem_cliff_1e5": (dem_cliff, [], "fit", None),
    "offset_1e7": (offset_1e7, [], "fit", None),
    "offset_1e7_tol1e-7": (offset_1e7, ["--tol-rel", "1e-7"], "fit", None),
    "tol_1e-7": (smooth_small, ["--tol-rel", "1e-7"], "fit", None),
    "tol_1e-9": (smooth_small, ["--tol-rel", "1e-9"], "fit", None),
    "tol_axis_zero": (smooth_small, ["--tol", "0.002,0.002,0"], "fit", None),
    "middle_pole": (middle_pole, ["--closed", "u"], "fit", None),
    "many_tiny_rows": (many_tiny_rows, [], "fit", None),
    "all_two_point_rows": (all_two_point_rows, [], "fit", None),
    "two_point_rows_wave": (two_point_rows_wave, [], "fit", None),
    "mixed_closed": (mixed_closed, ["--closed", "u"], "fit", None),
    "tiny_rows_1e5": (tiny_rows_1e5, [], "fit", None),
    "offset_1e8_tol1e-9": (offset_1e8, ["--tol-rel", "1e-9"], "fit", None),
    "ragged_uneven": (ragged_uneven, [], "fit", None),
    "ragged_uneven_1e-2": (ragged_uneven, ["--tol-rel", "1e-2"], "fit", None),
    "dem_cliff_1e5_1e-9": (dem_cliff, ["--tol-rel", "1e-9"], "fit", None),
    "crlf": (smooth_small, [], "fit", crlf),
    "blank_lines": (smooth_small, [], "fit", blank_lines),
    "nan_value": (smooth_small, [], "input", put_nan),
    "inf_value": (smooth_small, [], "input", put_inf),
    "two_numbers": (smooth_small, [], "input", two_numbers),
    "beyond_double": (smooth_small, [], "input", huge_number),
    "one_row": (one_row, [], "input", None),
    "empty_file": (smooth_small, [], "input", empty),
    "comments_only": (smooth_small, [], "input", comments_only),
}

CHEAP_POINTS = 20000  # below this many points, also write STL, OBJ (and STEP where built)


def rows_text(rows):
    out = ["# generated by bench/adversarial.py"]
    for r in rows:
        out.extend(f"{p[0]:.17g} {p[1]:.17g} {p[2]:.17g}" for p in r)
        out.append("")
    return "\n".join(out) + "\n"


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
