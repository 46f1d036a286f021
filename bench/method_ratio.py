#!/usr/bin/env python3
"""The default (--method surface) against the two stages alone (--method sfit01), same run.

  bench/method_ratio.py [SFIT] [--reps N] [--sets DIR ...] [--large N]   (--sets alone: no sets)

Every example set (examples/*.rows, closed flags as scripts/paper_table.py states them) at
--tol-rel 1e-2, 1e-3 and 1e-4, each method in turn, median of N runs (default 5) of the fit
time from the report (reading and writing excluded). Prints a Markdown table with the ratio
default / sfit01 (the default must stay within 1.5x) and the counts of both.
--large N: also three generated sets of 10^6 points, whole CLI runs (parse to written JSON),
N runs each (median): a smooth 1000 x 1000 grid at 1e-3 (bench/run.sh's g1m), 10^6 smooth
points in 1000 ragged rows at 1e-3 (bench/peers/make_sets.py ragged), and the same grid's
field with uniform noise of +-T at T = 0.5; wall time, fit time, peak memory and its ratio
to the points' size (24 bytes a point).
"""
import json
import os
import statistics
import subprocess
import sys
import tempfile

root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
args = sys.argv[1:]
sfit = os.path.join(root, "build/apps/sfit/sfit")
reps = 5
large = 0
dirs = [os.path.join(root, "examples")]
while args:
    a = args.pop(0)
    if a == "--reps":
        reps = int(args.pop(0))
    elif a == "--large":
        large = int(args.pop(0))
    elif a == "--sets":
        dirs = []
        while args and not args[0].startswith("--"):
            dirs.append(args.pop(0))
    else:
        sfit = a
CLOSED_U = {"d150_wing.rows", "iea15mw_blade_af50.rows", "iea3p4mw_blade_ragged9.rows",
            "ring_body.rows", "bent_tube.rows", "spout_tube.rows", "teapot_body.rows",
            "teapot_handle.rows", "teapot_spout_small.rows"}


def fit(path, extra):
    with tempfile.TemporaryDirectory() as d:
        subprocess.run([sfit, "fit", path, "-q", "--report", f"{d}/r.json"] + extra, check=True)
        with open(f"{d}/r.json") as f:
            return json.load(f)


print(f"Fit time from the report, median of {reps} runs, the two methods alternating.\n")
print("| data set | tolerance | default nu x nv | sfit01 nu x nv | default ms | sfit01 ms | ratio |")
print("|---|---|---|---|---|---|---|")
worst = 0.0
for d in dirs:
    for name in sorted(os.listdir(d)):
        if not name.endswith(".rows"):
            continue
        path = os.path.join(d, name)
        for rel in ("1e-2", "1e-3", "1e-4"):
            base = ["--tol-rel", rel] + (["--closed", "u"] if name in CLOSED_U else [])
            t = {"surface": [], "sfit01": []}
            r = {}
            for _ in range(reps):
                for m in t:
                    r[m] = fit(path, base + ["--method", m])
                    t[m].append(r[m]["seconds"])
            a, b = statistics.median(t["surface"]), statistics.median(t["sfit01"])
            ratio = a / b
            worst = max(worst, ratio)
            cu = lambda x: "x".join(str(c) for c in x["control_points"])
            print(f"| {name} | {rel} diag | {cu(r['surface'])} | {cu(r['sfit01'])} | "
                  f"{1e3 * a:.2f} | {1e3 * b:.2f} | {ratio:.2f} |", flush=True)
print(f"\nLargest ratio default / sfit01: {worst:.2f} (target: at most 1.5)")

if not large:
    sys.exit(0)


def write_grid(path, noise):
    import math
    state = 12345
    with open(path, "w") as f:
        for i in range(1000):
            lines = []
            for j in range(1000):
                if noise:
                    state = (state * 6364136223846793005 + 1442695040888963407) % (1 << 64)
                    z = 10 * math.sin(0.01 * i) * math.cos(0.013 * j) + ((state >> 11) / 2**53 - 0.5)
                    lines.append("%d %d %.6f" % (i, j, z))
                else:
                    s_, t = j / 999, i / 999
                    z = 10 * math.sin(3 * s_) * math.cos(2 * t) + 5 * s_ * t * t + 0.5 * math.sin(17 * s_ + 11 * t)
                    lines.append(f"{100 * s_:.9g} {100 * t:.9g} {z:.9g}")
            f.write("\n".join(lines) + "\n\n")


with tempfile.TemporaryDirectory() as d:
    write_grid(f"{d}/grid_1e6.rows", False)
    write_grid(f"{d}/noisy_1e6.rows", True)
    subprocess.run([sys.executable, os.path.join(root, "bench/peers/make_sets.py"), d, "ragged",
                    "1000000"], check=True, capture_output=True)
    ragged = [n for n in os.listdir(d) if n.startswith("ragged_")][0]
    cases = [("smooth 1000 x 1000 grid", "grid_1e6.rows", ["--tol-rel", "1e-3"]),
             ("smooth, 1000 ragged rows", ragged, ["--tol-rel", "1e-3"]),
             ("1000 x 1000 grid, noise +-T", "noisy_1e6.rows", ["--tol", "0.5"])]
    print(f"\nWhole CLI runs on 10^6 points, {os.cpu_count()} cores, median of {large}.\n")
    print("| data set | T | method | nu x nv | wall s | fit s | peak MB | peak / points' size | pairs | stop |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for label, name, tol in cases:
        walls = {}
        for m in ("surface", "sfit01"):
            runs = []
            for _ in range(large):
                cmd = ["/usr/bin/time", "-f", "%e %M", "-o", f"{d}/time", sfit, "fit",
                       f"{d}/{name}", "-q", "-o", f"{d}/s.json", "--report", f"{d}/r.json",
                       "--method", m] + tol
                subprocess.run(cmd, check=True)
                wall, kb = open(f"{d}/time").read().split()[-2:]
                r = json.load(open(f"{d}/r.json"))
                runs.append((float(wall), int(kb), r))
            runs.sort(key=lambda x: x[0])
            wall, kb, r = runs[len(runs) // 2]
            walls[m] = wall
            mb = kb / 1024
            cu = "x".join(str(c) for c in r["control_points"])
            print(f"| {label} | {' '.join(tol)} | {'default' if m == 'surface' else m} | {cu} | "
                  f"{wall:.2f} | {r['seconds']:.2f} | {mb:.0f} | {mb / 24:.1f} | "
                  f"{r['pairs_tried']} | {r['stop_reason'][:60]} |", flush=True)
        print(f"| {label} | | default / sfit01 (wall) | | {walls['surface'] / walls['sfit01']:.2f} | | | | | |")
