#!/usr/bin/python3
"""Control points and time of the default method (the surface search) against --method sfit01
on every .rows file given, at fractions of the bounding-box diagonal; the Markdown table for
docs/control-points.md.

    scripts/control_points_table.py --sfit build/apps/sfit/sfit examples/*.rows
    scripts/control_points_table.py --generated /tmp/gen examples/*.rows   # + smooth grids

Closed rows are read from each file's header (a line saying the rows are CLOSED). With
--generated DIR the script also writes and measures a DEM-like height field of 10^5 points
and a wavy closed cylinder into DIR. Peers (OpenCASCADE, SISL, SciPy) are measured by
bench/peers/run_peers.py (docs/bench_peers.md), not here.
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile
import time

# Closed rows are told as the peer benchmark tells them (a header line "rows are CLOSED").
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "bench",
                                "peers"))
from run_peers import closed_u  # noqa: E402


def generate(folder):
    import numpy as np

    os.makedirs(folder, exist_ok=True)

    def write(path, rows):
        with open(path, "w") as f:
            f.write("# generated smooth data (scripts/control_points_table.py)\n")
            for k, r in enumerate(rows):
                if k:
                    f.write("\n")
                np.savetxt(f, r, fmt="%.6f")

    def h(x, y):
        return (40 * np.sin(1.3 * x + 0.4) * np.cos(0.9 * y)
                + 25 * np.exp(-((x - 2) ** 2 + (y - 3) ** 2)) + 10 * x * y / 25)

    dem = os.path.join(folder, "dem_height_field_1e5.rows")
    x = np.linspace(0, 5, 317)
    write(dem, [np.column_stack([x * 200, np.full(x.size, y * 200), h(x, y)])
                for y in np.linspace(0, 5, 316)])
    cyl = os.path.join(folder, "wavy_cylinder.rows")
    rows = []
    for t in np.linspace(0, 1, 60):
        a = np.linspace(0, 2 * np.pi, 120, endpoint=False)
        r = 1 + 0.15 * np.sin(3 * a) * np.cos(4 * t) + 0.1 * t
        rows.append(np.column_stack([r * np.cos(a), r * np.sin(a), np.full(a.size, 6 * t)]))
    write(cyl, rows)
    with open(cyl) as f:
        text = f.read()
    with open(cyl, "w") as f:
        f.write("# rows are CLOSED contours\n" + text)
    return [dem, cyl]


def fit(sfit, path, frac, closed, method):
    with tempfile.TemporaryDirectory() as d:
        rep = os.path.join(d, "r.json")
        cmd = [sfit, "fit", path, "--tol-rel", str(frac), "--method", method, "--report", rep,
               "-q"]
        if closed:
            cmd += ["--closed", "u"]
        t0 = time.monotonic()
        p = subprocess.run(cmd, capture_output=True, text=True)
        wall = time.monotonic() - t0
        if p.returncode != 0:
            return None
        r = json.load(open(rep))
        nu, nv = r["control_points"]
        return {"nu": nu, "nv": nv, "wall": wall, "within": r["within_tolerance"],
                "parameters": r["parameters"], "stop": r.get("stop_reason", ""),
                "method": r.get("method", method), "pairs": r.get("pairs_tried", 0)}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("files", nargs="*")
    ap.add_argument("--sfit", default="build/apps/sfit/sfit")
    ap.add_argument("--fractions", default="1e-2,1e-3")
    ap.add_argument("--generated", help="folder to write the generated smooth sets into")
    a = ap.parse_args()
    files = list(a.files)
    if a.generated:
        files += generate(a.generated)
    print("| data | T / diag | default nu x nv | rule | time s | sfit01 nu x nv | time s | ratio |")
    print("|---|---|---|---|---|---|---|---|")
    for path in files:
        closed = closed_u(path)
        for frac in [float(x) for x in a.fractions.split(",")]:
            d = fit(a.sfit, path, frac, closed, "surface")
            s = fit(a.sfit, path, frac, closed, "sfit01")
            name = os.path.basename(path)[:-5]
            if not d or not s:
                print(f"| {name} | {frac:g} | failed | | | | | |")
                continue
            nd, ns = d["nu"] * d["nv"], s["nu"] * s["nv"]
            rule = d["parameters"] if d["method"] == "surface" else "(sfit01's)"
            print(f"| {name} | {frac:g} | {d['nu']} x {d['nv']} = {nd} | {rule} | "
                  f"{d['wall']:.2f} | {s['nu']} x {s['nv']} = {ns} | {s['wall']:.2f} | "
                  f"{nd / ns:.2f} |")
            sys.stdout.flush()


if __name__ == "__main__":
    main()
