#!/usr/bin/env python3
"""SciPy's grid fitter for the peer benchmark: scipy.interpolate.RectBivariateSpline, bicubic.

  scipy_peer.py DATA.rows TOL SURFACE_OUT.json [--repeats R] [--budget SECONDS]

Applies to height fields on a rectilinear grid only (every row at one x, the same y values in
every row: the height-field sets of examples/ and the generated grids). Prints one JSON object;
the surface goes to SURFACE_OUT.json for `sfit_peers check` (the common checker).

FITPACK has no maximum-deviation tolerance, only the smoothing factor s (sum of squared
residuals). The closest honest equivalent of "fit within T" is what a user has to do: start at
s = N (T/2)^2 and divide s by 10 until every |residual| <= T (at most 8 tries, then s = 0,
interpolation). The time reported is that whole loop; `tries` says how many fits it took.
"""
import json
import sys
import time

import numpy as np
from scipy.interpolate import RectBivariateSpline


def read_rows(path):
    with open(path) as f:
        text = f.read()
    counts = []
    body = []
    n = 0
    for line in text.splitlines():
        line = line.split("#", 1)[0].strip()
        if not line:
            if n:
                counts.append(n)
                n = 0
            continue
        body.append(line.replace(",", " "))
        n += 1
    if n:
        counts.append(n)
    values = np.array(" ".join(body).split(), dtype=float).reshape(-1, 3)
    return values, counts


def fit(x, y, z, tol):
    s = z.size * (tol / 2) ** 2
    tries = 0
    while True:
        tries += 1
        spl = RectBivariateSpline(x, y, z, kx=3, ky=3, s=s)
        if np.max(np.abs(spl(x, y) - z)) <= tol or s == 0:
            return spl, s, tries
        s = s / 10 if tries < 8 else 0.0


def main(argv):
    data, tol, out = argv[1], float(argv[2]), argv[3]
    repeats = int(argv[argv.index("--repeats") + 1]) if "--repeats" in argv else 5
    budget = float(argv[argv.index("--budget") + 1]) if "--budget" in argv else 30.0
    pts, counts = read_rows(data)
    if len(set(counts)) != 1 or len(counts) < 4 or counts[0] < 4:
        print(json.dumps({"error": "not a grid"}))
        return 1
    m, n = len(counts), counts[0]
    P = pts.reshape(m, n, 3)
    # Either every row lies at one x and runs along y (height_field.rows), or at one y running along x
    # (topobathy); z is the height over that rectilinear (x, y) grid.
    for across, along in ((0, 1), (1, 0)):
        a, b = P[:, 0, across], P[0, :, along]
        if (np.allclose(P[:, :, across], a[:, None], rtol=0, atol=1e-9 * np.ptp(a))
                and np.allclose(P[:, :, along], b[None, :], rtol=0, atol=1e-9 * np.ptp(b))):
            break
    else:
        print(json.dumps({"error": "not a height field on a rectilinear grid"}))
        return 1
    x, y, z = a, b, P[:, :, 2]  # spline variables: x across the rows, y along them
    if x[0] > x[-1]:
        x, z = x[::-1], z[::-1, :]
    if y[0] > y[-1]:
        y, z = y[::-1], z[:, ::-1]
    times = []
    while not times or (len(times) < repeats and sum(times) < budget):
        t0 = time.perf_counter()
        spl, s, tries = fit(x, y, z, tol)
        times.append(time.perf_counter() - t0)
    tx, ty, c = spl.tck  # full knot vectors (ends repeated 4 times), coefficients x-major
    c = np.asarray(c).reshape(len(tx) - 4, len(ty) - 4)
    gx = np.array([tx[i + 1:i + 4].mean() for i in range(len(tx) - 4)])  # Greville abscissae:
    gy = np.array([ty[i + 1:i + 4].mean() for i in range(len(ty) - 4)])  # x(u) = u exactly

    def pole(i, j):
        q = [0.0, 0.0, float(c[i, j])]
        q[across], q[along] = float(gx[i]), float(gy[j])
        return q

    poles = [[pole(i, j) for j in range(len(gy))] for i in range(len(gx))]
    with open(out, "w") as f:
        json.dump({"degree_u": 3, "degree_v": 3, "knots_u": tx.tolist(), "knots_v": ty.tolist(),
                   "poles": poles}, f)
    st = sorted(times)
    k = len(st)
    median = st[k // 2] if k % 2 else 0.5 * (st[k // 2 - 1] + st[k // 2])
    print(json.dumps({"peer": "scipy-grid", "tolerance": tol, "points": int(pts.shape[0]),
                      "rows": m, "times": times, "median_s": median,
                      "coefficients": int(c.size), "shape": f"{c.shape[1]}x{c.shape[0]}",
                      "notes": f"s = {s:.4g} after {tries} fit(s)", "surface": out}))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
