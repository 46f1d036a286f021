#!/usr/bin/env python3
"""Fits a large height grid in overlapping tiles on a Dask cluster, one surface per tile.

A terrain model (DEM) or a scan too large for one fit is cut into tiles that overlap their
neighbours by a margin; each tile is fitted by sfit on a worker of a distributed.LocalCluster
(or any cluster given by --scheduler), with ONE absolute tolerance for all tiles, so every
tile surface is within T of every point it covers, and two neighbours differ by at most 2T
where they overlap. The workers return their results (the surface, its report and the fitted
points along the tile's edges); only the client writes: OUT/tile_<row>_<col>.json (surface +
report) per tile and OUT/summary.json with the seams, the largest difference between two
neighbours' surfaces at the points they share, per axis. For one surface over all the points
instead of tiles, see sfit.dask.fit (docs/python.md, "More than one machine").

    /usr/bin/python3 examples/python/dask_tiles.py -o tiles --size 2000 2000 --tile 250
    /usr/bin/python3 examples/python/dask_tiles.py -o tiles --input heights.npy --spacing 30 30

The height grid is --input (a 2-D .npy array of heights, rows along x; each worker reads the
tiles it fits from the file, memory-mapped) or a generated terrain of --size rows x columns.
Needs numpy, dask and distributed (Debian python3-dask, python3-distributed) and sfit
(PYTHONPATH=build/python or pip install .).
"""

import argparse
import json
import os
import tempfile
import time

import numpy as np


def terrain(rows, cols, seed=1):
    """A smooth synthetic terrain: a few hills and valleys of different sizes (metres)."""
    rng = np.random.default_rng(seed)
    y, x = np.mgrid[0:rows, 0:cols].astype(float)
    z = np.zeros((rows, cols))
    for _ in range(12):
        cx, cy = rng.uniform(0, cols), rng.uniform(0, rows)
        w = rng.uniform(0.05, 0.3) * max(rows, cols)
        z += rng.uniform(-40, 80) * np.exp(-((x - cx) ** 2 + (y - cy) ** 2) / (2 * w * w))
    z += 5 * np.sin(x / 37.0) * np.cos(y / 53.0)
    return z


def tile_ranges(n, tile, overlap):
    """[(start, stop)] of tiles of `tile` cells plus `overlap` on each side, clipped."""
    out = []
    for start in range(0, n - 1, tile):
        out.append((max(0, start - overlap), min(n, start + tile + overlap + 1)))
    return out


def fit_tile(key, z, x0, y0, dx, dy, tol, degree, band):
    """Worker task: fits one tile of heights z (rows along x); returns the surface (an
    sfit.Surface: it pickles), the report's numbers and the fitted points (the surface at each
    point's parameters) of the `band` rows and columns along each edge, for the seams."""
    import sfit  # imported in the worker process

    z = np.asarray(z, dtype=float)
    rows, cols = z.shape
    x = x0 + dx * np.arange(cols)
    y = y0 + dy * np.arange(rows)
    grid = np.empty((rows, cols, 3))
    grid[..., 0] = x[None, :]
    grid[..., 1] = y[:, None]
    grid[..., 2] = z
    fit = sfit.fit(grid, tol=tol, degree=degree, threads=1)
    # Each point's v: its own where the rule gives one (parameters geometric), else its row's.
    v = fit.v_points if len(fit.v_points) else np.repeat(fit.v, fit.row_sizes)
    fitted = fit.surface(fit.u, v).reshape(rows, cols, 3)
    r = fit.report
    return {
        "tile": list(key),
        "x": [float(x[0]), float(x[-1])],
        "y": [float(y[0]), float(y[-1])],
        "points": r["points"],
        "control_points": r["control_points"],
        "max_deviation": r["max_deviation"],
        "within_tolerance": r["within_tolerance"],
        "seconds": r["seconds"],
        "surface": fit.surface,
        "report": r,
        "edges": {"left": fitted[:, :band], "right": fitted[:, -band:],
                  "top": fitted[:band], "bottom": fitted[-band:]},
    }


def seams(tiles, ranges_r, ranges_c):
    """The largest |S_a - S_b| per axis over the points two neighbouring tiles share."""
    by_key = {tuple(t["tile"]): t for t in tiles}
    worst = np.zeros(3)
    for (i, j), a in by_key.items():
        if (i, j + 1) in by_key:  # shared columns: the end of a, the start of b
            w = ranges_c[j][1] - ranges_c[j + 1][0]
            b = by_key[(i, j + 1)]
            worst = np.maximum(worst, np.abs(a["edges"]["right"][:, -w:] -
                                             b["edges"]["left"][:, :w]).reshape(-1, 3).max(0))
        if (i + 1, j) in by_key:
            w = ranges_r[i][1] - ranges_r[i + 1][0]
            b = by_key[(i + 1, j)]
            worst = np.maximum(worst, np.abs(a["edges"]["bottom"][-w:] -
                                             b["edges"]["top"][:w]).reshape(-1, 3).max(0))
    return worst


def write_json(path, value):
    """Writes through a temporary file and a rename: a summary is complete or absent."""
    folder = os.path.dirname(os.path.abspath(path))
    with tempfile.NamedTemporaryFile("w", dir=folder, delete=False, suffix=".tmp") as f:
        json.dump(value, f, indent=2)
        f.write("\n")
    os.replace(f.name, path)


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("-o", "--out", required=True, help="output folder (created)")
    p.add_argument("--input", help="2-D .npy array of heights (default: a generated terrain)")
    p.add_argument("--size", type=int, nargs=2, default=[1000, 1000], metavar=("ROWS", "COLS"))
    p.add_argument("--spacing", type=float, nargs=2, default=[1.0, 1.0], metavar=("DX", "DY"))
    p.add_argument("--tile", type=int, default=200, help="cells per tile side (default 200)")
    p.add_argument("--overlap", type=int, default=10, help="cells of overlap on each side")
    p.add_argument("--tol", type=float, help="absolute tolerance (default: 1e-3 of the whole "
                   "grid's bounding-box diagonal, the same for every tile)")
    p.add_argument("--degree", type=int, default=3)
    p.add_argument("--workers", type=int, default=2)
    p.add_argument("--threads-per-worker", type=int, default=1)
    p.add_argument("--processes", action="store_true", help="workers as processes (default threads)")
    p.add_argument("--scheduler", help="address of an existing Dask scheduler instead of a LocalCluster")
    p.add_argument("--progress", action="store_true", help="distributed.progress() bar")
    a = p.parse_args(argv)

    import dask
    import dask.array as da
    from distributed import Client, LocalCluster, progress

    heights = np.load(a.input, mmap_mode="r") if a.input else terrain(*a.size)
    if heights.ndim != 2:
        p.error(f"--input must hold a 2-D array of heights, got shape {heights.shape}")
    # A memory-mapped --input is read by the workers, each the tiles it fits.
    z = da.from_array(heights, chunks=(a.tile, a.tile))
    dx, dy = a.spacing
    rows, cols = z.shape
    if a.tol is None:
        zmin, zmax = dask.compute(z.min(), z.max())
        extent = np.array([dx * (cols - 1), dy * (rows - 1), float(zmax - zmin)])
        a.tol = 1e-3 * float(np.linalg.norm(extent))

    start = time.perf_counter()
    cluster = None
    if a.scheduler:
        client = Client(a.scheduler)
    else:
        cluster = LocalCluster(n_workers=a.workers, threads_per_worker=a.threads_per_worker,
                               processes=a.processes, dashboard_address=None)
        client = Client(cluster)
    ranges_r = tile_ranges(rows, a.tile, a.overlap)
    ranges_c = tile_ranges(cols, a.tile, a.overlap)
    band = 2 * a.overlap + 1
    try:
        tasks = [dask.delayed(fit_tile, pure=True)((ti, tj), z[r0:r1, c0:c1], c0 * dx, r0 * dy,
                                                   dx, dy, a.tol, a.degree, band)
                 for ti, (r0, r1) in enumerate(ranges_r) for tj, (c0, c1) in enumerate(ranges_c)]
        futures = client.compute(tasks)
        if a.progress:
            progress(futures)
        tiles = client.gather(futures)
    finally:
        client.close()
        if cluster is not None:
            cluster.close()
    # Only the client writes: each tile's surface and report, then the summary.
    os.makedirs(a.out, exist_ok=True)
    for t in tiles:
        t["file"] = f"tile_{t['tile'][0]}_{t['tile'][1]}.json"
        doc = t["surface"].to_json()
        doc["report"] = t["report"]
        write_json(os.path.join(a.out, t["file"]), doc)
    seam = seams(tiles, ranges_r, ranges_c)
    for t in tiles:
        for k in ("surface", "report", "edges"):
            del t[k]
    tiles.sort(key=lambda t: t["tile"])
    summary = {
        "grid": [rows, cols],
        "spacing": [dx, dy],
        "tile": a.tile,
        "overlap": a.overlap,
        "tolerance": a.tol,
        "degree": a.degree,
        "tiles": tiles,
        "all_within_tolerance": all(t["within_tolerance"] for t in tiles),
        "control_points": sum(t["control_points"][0] * t["control_points"][1] for t in tiles),
        "seam": seam.tolist(),
        "seam_over_tolerance": float(seam.max() / a.tol) if a.tol > 0 else 0.0,
        "fit_seconds": sum(t["seconds"] for t in tiles),
        "wall_seconds": time.perf_counter() - start,
    }
    write_json(os.path.join(a.out, "summary.json"), summary)
    print(f"dask_tiles: {len(tiles)} tiles of {rows} x {cols} heights, T = {a.tol:.4g}, "
          f"{summary['control_points']} control points, within tolerance: "
          f"{'yes' if summary['all_within_tolerance'] else 'NO'}, seams up to "
          f"{summary['seam_over_tolerance']:.3f} T, "
          f"{summary['wall_seconds']:.2f} s wall, {summary['fit_seconds']:.2f} s fitting")
    return 0 if summary["all_within_tolerance"] else 1


if __name__ == "__main__":
    raise SystemExit(main())
