#!/usr/bin/python3
"""Generated data of the kinds users bring, fitted by the CLI's default: counts against points.

Each case is made here from a formula and a seeded random generator, so nobody tunes for a
file: scan lines clipped by a round boundary, a range image with holes, rows sampled unevenly,
hand-drawn closed contours, sections with sharp corners, a terrain grid of 10^5 points, an
airborne LiDAR tile with buildings and trees, and one case moved far from the origin; and,
added 2026-12-03 (bench/scan_shapes.py), an aircraft fuselage, a wind blade of ragged closed
sections, ship stations with a chine and a deck corner, a 344 x 403 DEM with a river valley and
a range image with noise near T and a large irregular hole. For each, at 1e-2 and 1e-3 of the bounding-box diagonal, the
table gives the points, the control points of the default fit (nu x nv), their ratio to the
points, the rule that made the surface, whether the report says it holds T, the fold measure,
the CLI's wall time, and whether the report says that T forces interpolation (where more
control points than points are allowed).

    bench/scan_cases.py build/apps/sfit/sfit [--only NAME] [--tol 1e-2,1e-3] [--seed 7] [--stop]

`--seed` draws the cases again from another seed of the random generator (default 7, the
seed of every number quoted in docs/); `--stop` prints each report's stop reason (its first
160 characters) under its line.
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

from scan_shapes import (dem_river, fuselage, hull_variants, range_hole_noise, ship_stations,
                         wind_blade)


def field(x, y):
    """A smooth terrain-like height: two bumps and a gentle wave (units of the domain)."""
    return (0.35 * np.exp(-((x - 0.3) ** 2 + (y + 0.2) ** 2) / 0.18)
            - 0.25 * np.exp(-((x + 0.4) ** 2 + (y - 0.35) ** 2) / 0.09)
            + 0.08 * np.sin(2.5 * x + 1.3 * y))


def clipped_scan_lines(rng):
    """Scan lines y = const over a disk of radius 1, points every ~0.01 along x, so the rows
    run from 3 to 200 points and cover different parts of the surface."""
    rows = []
    for y in np.linspace(-0.98, 0.98, 120):
        half = math.sqrt(1 - y * y)
        n = max(3, int(2 * half / 0.01))
        x = np.sort(rng.uniform(-half, half, n))
        yy = y + rng.normal(0, 0.001, n)
        rows.append(np.column_stack([x, yy, field(x, yy)]))
    return rows


def range_image_with_holes(rng):
    """A 160 x 160 range image of a smooth part, with two holes where nothing was measured:
    a row that crosses a hole keeps the points on both sides."""
    rows = []
    xs = np.linspace(-1, 1, 160)
    for y in np.linspace(-1, 1, 160):
        keep = ((xs - 0.3) ** 2 / 0.06 + (y - 0.2) ** 2 / 0.12 > 1) & \
               ((xs + 0.5) ** 2 / 0.02 + (y + 0.5) ** 2 / 0.05 > 1)
        x = xs[keep]
        if len(x) < 2:
            continue
        z = 0.6 * np.sqrt(np.maximum(0, 1.6 - 0.5 * x * x - 0.4 * y * y)) + field(x, y) * 0.3
        rows.append(np.column_stack([x, np.full_like(x, y), z]))
    return rows


def uneven_rows(rng):
    """200 rows of 70 ... 130 points, each crowded in its own place (a random power warp)."""
    rows = []
    for y in np.linspace(-1, 1, 200):
        n = int(rng.integers(70, 131))
        t = np.sort(rng.uniform(0, 1, n))
        t[0], t[-1] = 0, 1
        t = t ** rng.uniform(0.5, 2.0)
        x = -1 + 2 * t
        rows.append(np.column_stack([x, np.full_like(x, y) + 0.05 * x * x, field(x, y)]))
    return rows


def closed_contours(rng, wobble=0.0003):
    """30 hand-drawn closed sections of a varying tube: each with its own point count, start
    angle and uneven angular spacing, a little wobble of the hand (`wobble` in radius)."""
    rows = []
    for k, zc in enumerate(np.linspace(0, 3, 30)):
        n = int(rng.integers(40, 140))
        a = np.sort(rng.uniform(0, 2 * math.pi, n)) + rng.uniform(0, 2 * math.pi)
        r = 1 + 0.3 * math.sin(zc) + 0.15 * np.cos(2 * a) + rng.normal(0, wobble, n)
        rows.append(np.column_stack([r * np.cos(a) * 1.4, r * np.sin(a), np.full(n, zc)]))
    return rows


def shaky_closed_contours(rng):
    """The closed sections drawn by a shakier hand: a wobble of up to 0.007, above T at 1e-3
    (0.0055), so T forces interpolation there, which the report must say."""
    return closed_contours(rng, wobble=0.002)


def cornered_sections(rng):
    """40 hull-like sections with a chine and a deck corner whose place along the section moves
    from bow to stern; 150 ... 400 points each, spaced unevenly."""
    rows = []
    for x in np.linspace(0, 40, 40):
        beam = 6 + 2 * math.sin(x / 40 * math.pi)
        depth = 4 + 0.02 * x
        corner = 0.35 + 0.3 * x / 40  # where along the section the chine is
        n = int(rng.integers(150, 401))
        t = np.sort(rng.uniform(0, 1, n))
        t[0], t[-1] = 0, 1
        pts = []
        for s in t:  # keel (0, 0) -> chine (0.8 beam, 0.3 depth) -> deck edge (beam, depth)
            if s < corner:
                w = s / corner
                y, z = 0.8 * beam * w, 0.3 * depth * w ** 1.5
            else:
                w = (s - corner) / (1 - corner)
                y = 0.8 * beam + 0.2 * beam * math.sin(w * math.pi / 2)
                z = 0.3 * depth + 0.7 * depth * w
            pts.append((x, y, z))
        rows.append(np.array(pts))
    return rows


def terrain_grid(rng):
    """A 330 x 320 grid (105,600 points) of terrain, 10 m spacing, heights in m: 60 random
    hills and hollows from 50 m to 800 m across."""
    xs = np.linspace(-1, 1, 330)
    c = rng.uniform(-1.1, 1.1, (60, 2))
    w = np.exp(rng.uniform(math.log(0.03), math.log(0.5), 60))
    h = rng.normal(0, 1, 60) * np.sqrt(w) * 80  # rough: small hills are not flat
    rows = []
    for y in np.linspace(-1, 1, 320):
        z = sum(h[k] * np.exp(-((xs - c[k, 0]) ** 2 + (y - c[k, 1]) ** 2) / w[k] ** 2)
                for k in range(60))
        rows.append(np.column_stack([xs * 1650, np.full_like(xs, y * 1600), z]))
    return rows


def lidar_tile(rng):
    """Airborne LiDAR over a 500 m square tile: gentle terrain, 40 flat-roofed buildings (5 to
    15 m high) and 400 trees (3 to 12 m), scanned in lines 1.5 m apart at 30 degrees to the
    tile's edges, so each line is clipped by the tile (2 ... 400 points, about 1.7 m apart):
    about 10^5 points. Roofs and trees jump by more than T = 1e-2 of the diagonal."""
    bx = rng.uniform(20, 480, (40, 2))
    bs = rng.uniform(8, 30, (40, 2))
    bh = rng.uniform(5, 15, 40)
    tc = rng.uniform(0, 500, (400, 2))
    tr = rng.uniform(2, 5, 400)
    th = rng.uniform(3, 12, 400)

    def height(x, y):
        z = 20 * np.sin(x / 130) * np.cos(y / 170) + 0.02 * x
        for k in range(40):
            inside = (abs(x - bx[k, 0]) < bs[k, 0] / 2) & (abs(y - bx[k, 1]) < bs[k, 1] / 2)
            z = np.where(inside, z + bh[k], z)
        for k in range(400):
            d2 = ((x - tc[k, 0]) ** 2 + (y - tc[k, 1]) ** 2) / tr[k] ** 2
            z = z + np.where(d2 < 1, th[k] * (1 - d2), 0)
        return z

    a = math.radians(30)
    d = np.array([math.cos(a), math.sin(a)])  # along a line
    nrm = np.array([-d[1], d[0]])             # across the lines
    rows = []
    for off in np.arange(-360, 700, 1.5):
        t = np.arange(-800, 800, 1.7) + rng.uniform(-0.3, 0.3)
        p = off * nrm + np.outer(t, d)
        keep = (p[:, 0] >= 0) & (p[:, 0] <= 500) & (p[:, 1] >= 0) & (p[:, 1] <= 500)
        p = p[keep]
        if len(p) < 2:
            continue
        rows.append(np.column_stack([p, height(p[:, 0], p[:, 1])]))
    return rows


def lidar_corner_strip(rng):
    """The LiDAR tile's first 80 scan lines: the tile's corner, where the lines are clipped
    short (2 ... 300 points), with its roofs and trees: about 6,700 points."""
    return lidar_tile(rng)[:80]


def far_offset(rng):
    """The uneven rows, 3.7e6 m east and 5.8e6 m north: UTM-like coordinates."""
    return [r * 100 + np.array([3.7e6, 5.8e6, 120.0]) for r in uneven_rows(rng)]


CASES = {
    "clipped_scan_lines": (clipped_scan_lines, []),
    "range_image_holes": (range_image_with_holes, []),
    "uneven_rows": (uneven_rows, []),
    "closed_contours": (closed_contours, ["--closed", "u"]),
    "shaky_closed": (shaky_closed_contours, ["--closed", "u"]),
    "cornered_sections": (cornered_sections, []),
    "terrain_grid_1e5": (terrain_grid, []),
    "lidar_tile": (lidar_tile, []),
    "lidar_corner_strip": (lidar_corner_strip, []),
    "far_offset": (far_offset, []),
    # added 2026-12-03 (bench/scan_shapes.py): shapes the code was not developed on
    "fuselage": (fuselage, ["--closed", "u"]),
    "wind_blade": (wind_blade, ["--closed", "u"]),
    "ship_stations": (ship_stations, []),
    "hull_variants": (hull_variants, []),
    "dem_river": (dem_river, []),
    "range_hole_noise": (range_hole_noise, []),
}


def claim(stop):
    """What the report says about a count above the points: T forcing it (noise, jumps, rows
    that need every point alone), or that no surface below the points held under the rules
    searched (measured)."""
    if "T forces interpolation" in stop:
        return "report: T forces interpolation"
    if "no surface below the points held under the rules searched" in stop:
        return "report: none below the points held under the rules searched"
    return ""


def write_rows(path, rows):
    with open(path, "w") as f:
        f.write("# generated by bench/scan_cases.py\n")
        for r in rows:
            for p in r:
                f.write(f"{p[0]:.17g} {p[1]:.17g} {p[2]:.17g}\n")
            f.write("\n")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("cli")
    ap.add_argument("--only", default="")
    ap.add_argument("--tol", default="1e-2,1e-3")
    ap.add_argument("--seed", type=int, default=7, help="the random generator's seed")
    ap.add_argument("--extra", default="", help="more CLI options, e.g. '--method sfit01'")
    ap.add_argument("--save", default="", help="also write each case's rows to this directory")
    ap.add_argument("--stop", action="store_true", help="print each report's stop reason")
    a = ap.parse_args()
    tols = [float(t) for t in a.tol.split(",")]
    print(f"{'case':<20} {'tol':>6} {'points':>8} {'nu x nv':>11} {'cp/pts':>7} {'rule':>12} "
          f"{'held':>5} {'fold':>8} {'s':>7}  note")
    with tempfile.TemporaryDirectory() as tmp:
        for name, (make, opts) in CASES.items():
            if a.only and a.only not in name:
                continue
            rows = make(np.random.default_rng(a.seed))
            path = os.path.join(tmp, name + ".rows")
            write_rows(path, rows)
            if a.save:
                os.makedirs(a.save, exist_ok=True)
                write_rows(os.path.join(a.save, name + ".rows"), rows)
            npts = sum(len(r) for r in rows)
            for tol in tols:
                rep = os.path.join(tmp, "r.json")
                cmd = [a.cli, "fit", path, "--tol-rel", str(tol), "-q", "-o",
                       os.path.join(tmp, "s.json"), "--report", rep] + opts + a.extra.split()
                t0 = time.time()
                p = subprocess.run(cmd, capture_output=True, text=True)
                dt = time.time() - t0
                if p.returncode != 0:
                    print(f"{name:<20} {tol:>6g} {npts:>8} exit {p.returncode}: "
                          f"{p.stderr.strip()[:80]}")
                    continue
                r = json.load(open(rep))
                cu, cv = r["control_points"] if isinstance(r["control_points"], list) else (0, 0)
                print(f"{name:<20} {tol:>6g} {npts:>8} {cu:>5} x {cv:<5} {cu * cv / npts:>7.3f} "
                      f"{r['parameters']:>12} {str(r['within_tolerance']):>5} "
                      f"{r['fold']:>8.2g} {dt:>7.2f}  "
                      f"{claim(r['stop_reason']) if cu * cv > npts else ''}")
                if a.stop:
                    print(f"    stop: {r['stop_reason'][:160]}")
                sys.stdout.flush()


if __name__ == "__main__":
    main()
