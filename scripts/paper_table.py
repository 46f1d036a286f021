#!/usr/bin/env python3
"""Prints the paper-style results table and the count-search comparison of docs/benchmarks.md.

  scripts/paper_table.py [SFIT_BINARY]     (default build/apps/sfit/sfit)

For every data set of examples/ (table1_synthetic.rows at the paper's absolute tolerances):
the counts nu x nv, the max deviation reached (as a fraction of T), whether every point held,
and the fit time (median of 3 runs, from the report). Then, for the same fits, how the
default count search compares with the paper's linear search.
"""
import json
import os
import subprocess
import sys
import tempfile

root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sfit = sys.argv[1] if len(sys.argv) > 1 else os.path.join(root, "build/apps/sfit/sfit")
examples = os.path.join(root, "examples")
SETS = [  # file, closed rows
    ("d150_wing.rows", True), ("iea15mw_blade_af50.rows", True), ("iea3p4mw_blade_ragged9.rows", True),
    ("ship_px121_stations.rows", False), ("ring_body.rows", True), ("bent_tube.rows", True),
    ("spout_tube.rows", True), ("topobathy.rows", False), ("height_field.rows", False),
    ("height_field_small.rows", False),
]

def run(path, args, search="fast"):
    with tempfile.TemporaryDirectory() as d:
        reps = []
        for _ in range(3):
            subprocess.run([sfit, "fit", path, "-q", "-o", f"{d}/s.json", "--report", f"{d}/r.json",
                            "--method", "sfit01", "--search", search] + args, check=True)
            reps.append(json.load(open(f"{d}/r.json")))
        reps.sort(key=lambda r: r["seconds"])
        return reps[1]

def used(r):
    return max(m / t for m, t in zip(r["max_deviation"], r["tolerance"]) if t > 0)

jobs = []
for name, closed in SETS:
    p = os.path.join(examples, name)
    for rel in ("1e-2", "1e-3", "1e-4"):
        jobs.append((name, p, ["--tol-rel", rel] + (["--closed", "u"] if closed else []), f"{rel} diag"))
t1 = os.path.join(root, "examples", "table1_synthetic.rows")
for T in ("1", "10", "20", "100"):
    jobs.append(("table1_synthetic.rows (bicubic)", t1, ["--tol", T], f"T = {T}"))

print("| data set | rows | points | tolerance | nu x nv | max deviation / T | every point within T | fit time |")
print("|---|---|---|---|---|---|---|---|")
results = []
for name, p, args, label in jobs:
    r = run(p, args)
    results.append((name, p, args, label, r))
    print(f"| {name} | {r['rows']} | {r['points']} | {label} | {r['control_points'][0]} x {r['control_points'][1]} "
          f"| {used(r):.3f} | {'yes' if r['within_tolerance'] else 'NO'} | {1000 * r['seconds']:.2f} ms |")

print()
print("| data set | tolerance | nu x nv fast / linear | rows (columns) whose count differs | counts summed fast / linear | solves fast / linear |")
print("|---|---|---|---|---|---|")
for name, p, args, label, fast in results:
    lin = run(p, args, "linear")
    dr = sum(a != b for a, b in zip(fast["row_counts"], lin["row_counts"]))
    same_nu = fast["control_points"][0] == lin["control_points"][0]
    dc = sum(a != b for a, b in zip(fast["column_counts"], lin["column_counts"])) if same_nu else "n/a"
    sf = sum(fast["row_counts"]) + sum(fast["column_counts"])
    sl = sum(lin["row_counts"]) + sum(lin["column_counts"])
    print(f"| {name} | {label} | {fast['control_points'][0]} x {fast['control_points'][1]} / "
          f"{lin['control_points'][0]} x {lin['control_points'][1]} | {dr} ({dc}) | {sf} / {sl} | {fast['solves']} / {lin['solves']} |")
