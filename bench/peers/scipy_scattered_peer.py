#!/usr/bin/env python3
"""SciPy's scattered-data fitters for the peer benchmark: scipy.interpolate.LSQBivariateSpline
and SmoothBivariateSpline (FITPACK surfit), bicubic, for height fields that are not a full grid.

  scipy_scattered_peer.py DATA.rows TOL SURFACE_OUT.json [--repeats R] [--budget SECONDS]
                          [--time-limit SECONDS]

Applies to height fields of any row shape: every point is z = f(x, y), rows may be clipped,
have holes or differ in length (scan lines clipped by an outline, range images with holes,
unevenly sampled rows, LiDAR strips). The rows' order is not used; the points are scattered
data over their (x, y) bounding box. Prints one JSON object; the surface goes to
SURFACE_OUT.json for `sfit_peers check` (the common closest-point checker).

T for this peer is the vertical residual: a fit holds T when |z - f(x, y)| <= T at every
point. The closest-point distance the common checker measures is never larger, so a fit that
holds T here holds it there too.

Two loops, each what a user who wants the fewest coefficients within T writes; the fit with
fewer coefficients is kept. First, uniform interior knots, the same number g on x and y (g = 0, 1, 2, 4, 8, ... doubling until a fit holds T at
every point, then bisection between the last g that failed and the first that held), each fit
a least-squares LSQBivariateSpline checked on every residual. (FITPACK solves a rank-deficient
system, knot cells without data, by its minimal-norm solution, so holes do not stop it.) The
loop stops at --time-limit seconds (default 120). Coefficients are (g + 4)^2. Second, while
time remains, SmoothBivariateSpline (surfit places its own knots) at s = N (T/2)^2, s divided by
10 until every vertical residual holds T (at most 8 tries). A case where neither loop held T
reports an error. The time reported is both loops; the notes say which fit was kept and how
many fits were made.
"""
import json
import sys
import time
import warnings

import numpy as np
from scipy.interpolate import LSQBivariateSpline, SmoothBivariateSpline

from scipy_peer import read_rows


def fit_g(x, y, z, g, box):
    """The least-squares bicubic with g uniform interior knots on x and on y."""
    x0, x1, y0, y1 = box
    tx = np.linspace(x0, x1, g + 2)[1:-1]
    ty = np.linspace(y0, y1, g + 2)[1:-1]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the rank-deficiency note of FITPACK (holes)
        spl = LSQBivariateSpline(x, y, z, tx, ty, bbox=[x0, x1, y0, y1], kx=3, ky=3)
    return spl, float(np.max(np.abs(spl.ev(x, y) - z)))


def search(x, y, z, tol, time_limit):
    """Fewest g whose fit holds T: doubling, then bisection. Returns (spline, g, tries, worst
    residual of the kept fit) or (None, last g tried, tries, its worst residual)."""
    box = (x.min(), x.max(), y.min(), y.max())
    t0 = time.perf_counter()
    tries = 0
    held = {}  # g -> (spline, worst)
    failed = -1
    g = 0
    last = (None, 0, float("inf"))
    while True:
        tries += 1
        spl, worst = fit_g(x, y, z, g, box)
        last = (spl, g, worst)
        if worst <= tol:
            held[g] = (spl, worst)
            break
        failed = g
        # More interior knots than points per side leave nothing to fit: stop there.
        if g * g > x.size or time.perf_counter() - t0 > time_limit:
            return None, g, tries, worst
        g = 1 if g == 0 else 2 * g
    lo, hi = failed, g  # lo fails (or -1), hi holds
    while hi - lo > 1 and time.perf_counter() - t0 <= time_limit:
        mid = (lo + hi) // 2
        tries += 1
        spl, worst = fit_g(x, y, z, mid, box)
        if worst <= tol:
            hi = mid
            held[mid] = (spl, worst)
        else:
            lo = mid
    spl, worst = held[hi]
    del last
    return spl, hi, tries, worst


def search_smooth(x, y, z, tol, time_left):
    """SmoothBivariateSpline with s = N (T/2)^2 divided by 10 until T holds: (spline, s, tries,
    worst) or None."""
    t0 = time.perf_counter()
    s = x.size * (tol / 2) ** 2
    for tries in range(1, 9):
        if time.perf_counter() - t0 > time_left:
            return None
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")  # surfit's notes on s and rank
                spl = SmoothBivariateSpline(x, y, z, kx=3, ky=3, s=s)
        except (ValueError, MemoryError):
            return None
        worst = float(np.max(np.abs(spl.ev(x, y) - z)))
        if worst <= tol:
            return spl, s, tries, worst
        s /= 10
    return None


def both(x, y, z, tol, time_limit):
    """The fewer coefficients of the two loops: (spline, notes) or (None, why)."""
    t0 = time.perf_counter()
    spl, g, tries, worst = search(x, y, z, tol, time_limit)
    sm = search_smooth(x, y, z, tol, time_limit - (time.perf_counter() - t0))
    size = lambda f: (len(f.get_knots()[0]) - 4) * (len(f.get_knots()[1]) - 4)  # noqa: E731
    if sm is not None and (spl is None or size(sm[0]) < size(spl)):
        return sm[0], (f"SmoothBivariateSpline s = {sm[1]:.3g}, vertical residual "
                       f"{sm[3]:.3g}, {sm[2]} fit(s); LSQ uniform: "
                       + (f"{size(spl)} at g = {g}" if spl is not None else "none within T"))
    if spl is None:
        return None, (f"no fit within T: LSQ to g = {g} interior knots a side ({tries} fits, "
                      f"worst residual {worst:.3g} > T {tol:.3g}), SmoothBivariateSpline none")
    return spl, (f"LSQ g = {g} uniform interior knots a side, vertical residual {worst:.3g}, "
                 f"{tries} fit(s); SmoothBivariateSpline: "
                 + (f"{size(sm[0])}" if sm is not None else "none within T"))


def main(argv):
    data, tol, out = argv[1], float(argv[2]), argv[3]

    def opt(name, default):
        return type(default)(argv[argv.index(name) + 1]) if name in argv else default

    repeats, budget = opt("--repeats", 5), opt("--budget", 30.0)
    time_limit = opt("--time-limit", 120.0)
    pts, counts = read_rows(data)
    if pts.shape[0] < 16:
        print(json.dumps({"error": "fewer than 16 points"}))
        return 1
    # Centre the coordinates (FITPACK works in double on raw values; UTM-like offsets would
    # cost digits) and move them back on the poles.
    c = pts.mean(axis=0)
    x, y, z = pts[:, 0] - c[0], pts[:, 1] - c[1], pts[:, 2] - c[2]
    times = []
    while not times or (len(times) < repeats and sum(times) < budget):
        t0 = time.perf_counter()
        spl, notes = both(x, y, z, tol, time_limit)
        times.append(time.perf_counter() - t0)
        if spl is None:
            print(json.dumps({"error": notes}))
            return 1
    tx, ty = spl.get_knots()  # full knot vectors, ends repeated 4 times
    # LSQBivariateSpline's get_knots gives full vectors; the coefficients are x-major.
    cf = np.asarray(spl.get_coeffs()).reshape(len(tx) - 4, len(ty) - 4)
    gx = np.array([tx[i + 1:i + 4].mean() for i in range(len(tx) - 4)])  # Greville abscissae:
    gy = np.array([ty[i + 1:i + 4].mean() for i in range(len(ty) - 4)])  # x(u) = u exactly
    poles = [[[float(gx[i] + c[0]), float(gy[j] + c[1]), float(cf[i, j] + c[2])]
              for j in range(len(gy))] for i in range(len(gx))]
    with open(out, "w") as f:
        json.dump({"degree_u": 3, "degree_v": 3, "knots_u": (tx + c[0]).tolist(),
                   "knots_v": (ty + c[1]).tolist(), "poles": poles}, f)
    st = sorted(times)
    k = len(st)
    median = st[k // 2] if k % 2 else 0.5 * (st[k // 2 - 1] + st[k // 2])
    print(json.dumps({"peer": "scipy-scattered", "tolerance": tol, "points": int(pts.shape[0]),
                      "rows": len(counts), "times": times, "median_s": median,
                      "coefficients": int(cf.size), "shape": f"{cf.shape[0]}x{cf.shape[1]}",
                      "notes": notes, "surface": out}))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
