"""More generated cases for bench/scan_cases.py (2026-12-03): shapes and samplings that the
first set does not have, written after the code was developed, so that it is tried on data
nobody tuned for. Each function takes a numpy random generator and returns a list of rows
(arrays of points, one row a section or a scan line)."""

import math

import numpy as np


def _uneven(rng, n, lo=0.4, hi=2.5):
    """n sorted parameters in [0, 1), crowded unevenly: a random power warp plus clusters."""
    t = np.sort(rng.uniform(0, 1, n))
    t = t ** rng.uniform(lo, hi)
    # a cluster: a third of the points pulled towards a random place
    c = rng.uniform(0, 1)
    pull = rng.uniform(0, 1, n) < 0.33
    t = np.where(pull, c + (t - c) * 0.25, t)
    return np.sort(np.mod(t, 1.0))


def fuselage(rng):
    """An aircraft fuselage of 46 closed sections (about 4,700 points), 40 m long: a round nose
    that opens fast, a canopy bump on top behind the nose, a cylindrical middle and a tail
    that tapers and rises into a flattened oval. Each section has 60 ... 150 points crowded
    unevenly (a power warp and a cluster) and starts at its own random angle."""
    rows = []
    xs = 40 * (np.linspace(0, 1, 46) ** 1.15)
    xs[0] = 0.15
    for x in xs:
        s = x / 40
        r = 2.0 * math.sqrt(min(1.0, s / 0.12)) if s < 0.12 else 2.0
        if s > 0.7:  # tail: shrink and rise
            r = 2.0 - 1.6 * ((s - 0.7) / 0.3) ** 1.3
        zc = 1.4 * max(0.0, (s - 0.7) / 0.3) ** 1.6
        hw = r * (1.0 - 0.25 * max(0.0, (s - 0.7) / 0.3))  # half width
        hh = r * (1.0 + 0.05 * math.sin(3 * s))             # half height
        bump = 0.7 * math.exp(-((s - 0.13) / 0.035) ** 2)   # the canopy
        n = int(rng.integers(60, 151))
        a = 2 * math.pi * _uneven(rng, n) + rng.uniform(0, 2 * math.pi)
        a = np.unique(np.mod(a, 2 * math.pi))
        a = a[np.diff(np.append(a, a[0] + 2 * math.pi)) > 1e-6]
        up = np.maximum(0.0, np.sin(a)) ** 6  # only near the top
        y = hw * np.cos(a)
        z = zc + hh * np.sin(a) + bump * up - 0.15 * r * np.sin(a) ** 2
        rows.append(np.column_stack([np.full(len(a), x), y, z]))
    return rows


def _airfoil(t_c, camber, n, rng, blunt):
    """A closed airfoil of about n points (chord 1, leading edge at 0), NACA-like thickness
    t_c and camber; blunt > 0 gives a flat trailing edge of that thickness (sharp when 0).
    Points crowded at the nose and the tail (cosine spacing of random parameters): lower
    surface from the trailing edge to the nose, upper back, then the flat edge if any."""
    def half(k):
        return np.sort(0.5 * (1 - np.cos(math.pi * rng.uniform(0, 1, k))))

    def thick(x):
        return 5 * t_c * (0.2969 * np.sqrt(x) - 0.126 * x - 0.3516 * x ** 2
                          + 0.2843 * x ** 3 - 0.1036 * x ** 4) + blunt / 2 * x

    xl = np.concatenate([[1.0], half(n // 2)[::-1]])      # TE -> LE
    xu = np.concatenate([half(n - n // 2 - 4), [1.0]])    # LE -> TE
    xu = xu[xu > xl.min() + 1e-9] if xl.min() == 0 else xu
    yl = camber * 4 * xl * (1 - xl) - thick(xl)
    yu = camber * 4 * xu * (1 - xu) + thick(xu)
    pts = np.vstack([np.column_stack([xl, yl]), np.column_stack([xu, yu])])
    if blunt > 0:  # the flat trailing edge, from the upper TE down towards the lower TE
        te = np.linspace(yu[-1], yl[0], 6)[1:-1]
        pts = np.vstack([pts, np.column_stack([np.ones(4), te])])
    _, keep = np.unique(np.round(pts, 12), axis=0, return_index=True)
    return pts[np.sort(keep)]


def wind_blade(rng, sections=11):
    """A wind-turbine blade of `sections` ragged closed sections along 60 m: a round root
    that turns into thick, then thin airfoils (trailing edge blunt near the root, sharp
    outboard), with twist falling from 15 to 0 degrees, chord peaking at 20 %; each section
    150 ... 600 points, jittered, starting at its own point."""
    rows = []
    zs = 60 * np.sort(np.concatenate([[0.0, 1.0], rng.uniform(0.02, 0.98, sections - 2)]))
    for z in zs:
        s = z / 60
        chord = 2.5 + 2.2 * math.exp(-((s - 0.2) / 0.15) ** 2) - 1.5 * s
        t_c = 1.0 if s < 0.04 else max(0.18, 1.0 - 4.5 * (s - 0.04))
        blunt = max(0.0, 0.25 * (1 - s / 0.4))
        twist = math.radians(15 * (1 - s) ** 2)
        n = int(rng.integers(150, 601))
        if t_c >= 0.99:  # the root: a circle
            a = np.sort(rng.uniform(0, 2 * math.pi, n))
            p = np.column_stack([0.5 + 0.5 * np.cos(a), 0.5 * np.sin(a)])
        else:
            p = _airfoil(t_c, 0.03 * (1 - t_c), n, rng, blunt)
        p = (p - [0.3, 0]) * chord
        c, sn = math.cos(twist), math.sin(twist)
        p = p @ np.array([[c, sn], [-sn, c]])
        p = p + rng.normal(0, 2e-4 * chord, p.shape)
        k = int(rng.integers(0, len(p)))
        p = np.roll(p, -k, axis=0)
        rows.append(np.column_stack([p, np.full(len(p), z)]))
    return rows


def ship_stations(rng):
    """28 open ship stations (180 ... 460 points each, spaced unevenly) of a hard-chine hull
    with a deck corner: keel -> bottom -> chine -> side -> deck corner -> deck to centre.
    The chine's radius goes from 0 (a knuckle) amidships to 1.5 m forward; the deck corner
    is sharp aft and rounded (0.4 m) forward; the bow stations are narrow and V-shaped."""
    rows = []
    for x in np.linspace(0, 70, 28):
        s = x / 70
        beam = 5.5 * (1 - (max(0.0, s - 0.6) / 0.4) ** 1.8) + 0.4
        deadrise = math.radians(12 + 30 * max(0.0, s - 0.55) / 0.45)
        depth = 5.0 + 1.0 * s ** 2
        r_chine = 1.5 * abs(s - 0.45) / 0.55 if s > 0.45 else 0.0
        r_deck = 0.4 * max(0.0, s - 0.5) / 0.5
        chine_y = 0.85 * beam
        chine_z = chine_y * math.tan(deadrise)
        corners = np.array([[0, 0], [chine_y, chine_z], [beam, chine_z + 0.3],
                            [beam, depth], [0, depth + 0.15]])
        radii = [0.0, r_chine, 0.0, r_deck, 0.0]
        rows.append(_station(rng, x, corners, radii, 180, 461))
    return rows


def _station(rng, x, corners, radii, lo, hi):
    """A station at x: the polyline through corners (y, z) rounded by radii, lo ... hi - 1
    points spaced unevenly by arc length, both ends kept."""
    pts = _rounded_polyline(corners, radii)
    n = int(rng.integers(lo, hi))
    t = _uneven(rng, n, 0.6, 1.6)
    t[0], t[-1] = 0.0, 1.0
    t = np.unique(t)
    d = np.concatenate([[0], np.cumsum(np.linalg.norm(np.diff(pts, axis=0), axis=1))])
    y = np.interp(t * d[-1], d, pts[:, 0])
    z = np.interp(t * d[-1], d, pts[:, 1])
    return np.column_stack([np.full(len(y), x), y, z])


def _rounded_polyline(c, radii, per_arc=200):
    """A dense polyline through corners c with each inner corner rounded by its radius."""
    out = [c[0]]
    for k in range(1, len(c) - 1):
        a, b, d = c[k - 1], c[k], c[k + 1]
        r = radii[k]
        if r <= 0:
            out.append(b)
            continue
        u1 = (a - b) / np.linalg.norm(a - b)
        u2 = (d - b) / np.linalg.norm(d - b)
        ang = math.acos(np.clip(u1 @ u2, -1, 1))
        off = min(r / math.tan(ang / 2), 0.45 * np.linalg.norm(a - b),
                  0.45 * np.linalg.norm(d - b))
        p1, p2 = b + u1 * off, b + u2 * off
        w = np.linspace(0, 1, per_arc)[:, None]  # a quadratic Bezier: round enough here
        out.extend((1 - w) ** 2 * p1 + 2 * w * (1 - w) * b + w ** 2 * p2)
    out.append(c[-1])
    p = np.array(out, float)
    # a dense, evenly spaced polyline for interpolation by arc length
    d = np.concatenate([[0], np.cumsum(np.linalg.norm(np.diff(p, axis=0), axis=1))])
    keep = np.concatenate([[True], np.diff(d) > 1e-12])
    p, d = p[keep], d[keep]
    t = np.linspace(0, d[-1], 20000)
    return np.column_stack([np.interp(t, d, p[:, 0]), np.interp(t, d, p[:, 1])])


def dem_river(rng):
    """A DEM grid of 344 x 403 (138,632 points, 25 m spacing, heights in m): a meandering
    river valley cut 120 m into a plateau, two ridges across it and fine random relief."""
    nx, ny = 344, 403
    xs = np.arange(nx) * 25.0
    ph = rng.uniform(0, 2 * math.pi, 3)
    cs = rng.uniform(-1.2, 1.2, (30, 2))
    ws = np.exp(rng.uniform(math.log(0.02), math.log(0.15), 30))
    hs = rng.normal(0, 25, 30)
    rows = []
    for j in range(ny):
        y = j * 25.0
        X, Y = xs / (nx * 25.0), y / (ny * 25.0)
        river = 0.5 + 0.12 * math.sin(2 * math.pi * 1.5 * Y + ph[0]) \
            + 0.05 * math.sin(2 * math.pi * 4 * Y + ph[1])
        d = np.abs(X - river)
        z = 300 + 60 * Y - 120 * np.exp(-(d / 0.08) ** 2) - 30 * np.exp(-(d / 0.015) ** 2)
        z = z + 150 * np.exp(-((X - 0.2) * 0.8 + (Y - 0.3)) ** 2 / 0.004)  # ridge 1
        z = z + 110 * np.exp(-((X - 0.8) - 0.6 * (Y - 0.7)) ** 2 / 0.002)  # ridge 2
        Xc, Yc = 2 * X - 1, 2 * Y - 1
        for k in range(30):
            z = z + hs[k] * np.exp(-((Xc - cs[k, 0]) ** 2 + (Yc - cs[k, 1]) ** 2) / ws[k] ** 2)
        rows.append(np.column_stack([xs, np.full(nx, y), z]))
    return rows


def range_hole_noise(rng, level=0.9):
    """A 200 x 150 range image of a curved part (a saddle and a bump, 0.3 m across) with
    noise of `level` T at T = 1e-3 of the diagonal (uniform, so every point's noise is at most
    that) and a large irregular hole (a random star-shaped outline covering about a fifth of
    the image): a row crossing it keeps its two ends."""
    xs = np.linspace(0, 0.3, 200)
    ys = np.linspace(0, 0.22, 150)
    X, Y = np.meshgrid(xs, ys)
    Z = 0.04 * ((X - 0.15) ** 2 - (Y - 0.11) ** 2) / 0.01 + \
        0.02 * np.exp(-((X - 0.22) ** 2 + (Y - 0.06) ** 2) / 0.0015)
    diag = math.sqrt(0.3 ** 2 + 0.22 ** 2 + (Z.max() - Z.min()) ** 2)
    noise = level * 1e-3 * diag
    Z = Z + rng.uniform(-noise, noise, Z.shape)
    ang = np.arctan2(Y - 0.1, X - 0.13)
    h = rng.normal(0, 1, 5)
    g = rng.uniform(0, 2 * math.pi, 5)
    rad = 0.075 * (1 + 0.25 * sum(h[k] / (k + 1) * np.cos((k + 1) * ang + g[k])
                                  for k in range(5)))
    hole = np.hypot(X - 0.13, Y - 0.1) < rad
    rows = []
    for j in range(len(ys)):
        keep = ~hole[j]
        if keep.sum() >= 2:
            rows.append(np.column_stack([X[j, keep], Y[j, keep], Z[j, keep]]))
    return rows


def hull_variants(rng):
    """A hard-chine hull drawn from the seed: 16 ... 32 open stations (150 ... 400 points
    each, spaced unevenly) over 40 ... 90 m; keel -> bottom -> chine -> a short flare ->
    knuckle -> side -> deck corner -> deck. Every shape number is random: beam, deadrise,
    the knuckle's height above the chine (0.15 ... 0.6 m, so at 1e-3 of the diagonal it can
    sit within a few T of the chine), the flare's and the side's slopes (the knuckle turns by
    15 ... 50 degrees), fillet radii of the chine and deck corner growing forward, and a
    narrowing bow."""
    length = rng.uniform(40, 90)
    stations = int(rng.integers(16, 33))
    beam0 = rng.uniform(4, 9)
    depth0 = rng.uniform(3.5, 7)
    dead0 = rng.uniform(8, 20)
    knuckle_h = rng.uniform(0.15, 0.6)
    flare = rng.uniform(15, 45)  # degrees of the flare above the horizontal
    side = rng.uniform(65, 95)  # degrees of the side above the horizontal
    bow = rng.uniform(0.5, 0.7)  # where the bow starts narrowing
    r_chine_max = rng.uniform(0.0, 1.2)
    r_deck_max = rng.uniform(0.0, 0.6)
    camber = rng.uniform(0.0, 0.3)
    rows = []
    for x in np.sort(rng.uniform(0, length, stations)):
        s = x / length
        beam = beam0 * (1 - (max(0.0, s - bow) / (1 - bow)) ** 1.6) + 0.3
        dead = math.radians(dead0 + 25 * max(0.0, s - bow) / (1 - bow))
        depth = depth0 + 0.8 * s ** 2
        chine_y = 0.8 * beam
        chine_z = chine_y * math.tan(dead)
        fl = math.radians(flare)
        kn_y = chine_y + knuckle_h / math.tan(fl)
        kn_z = chine_z + knuckle_h
        sd = math.radians(side)
        top_y = kn_y + (depth - kn_z) / math.tan(sd)
        corners = np.array([[0, 0], [chine_y, chine_z], [kn_y, kn_z], [top_y, depth],
                            [0, depth + camber]])
        grow = max(0.0, s - 0.4) / 0.6
        radii = [0.0, r_chine_max * grow, 0.0, r_deck_max * grow, 0.0]
        rows.append(_station(rng, x, corners, radii, 150, 401))
    return rows
