#!/usr/bin/env python3
"""Prints the table of the four parameter rules (sfit fit --parameters) of docs/benchmarks.md.

  scripts/parameters_table.py [SFIT_BINARY]     (default build/apps/sfit/sfit)

For every data set of examples/ and
two generated sets of 10^5 points (bench/peers/make_sets.py: a terrain grid and unevenly
sampled ragged rows, written to build/parameters_sets/): the control points nu x nv each rule
gives, bicubic, default search, one thread, and the fit time from the report (median of 3).
"-> paper" marks a fit where the rule could not hold the tolerance and sfit fell back to the
paper's rule (the report's "parameters").
"""
import json
import os
import subprocess
import sys
import tempfile

root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sfit = sys.argv[1] if len(sys.argv) > 1 else os.path.join(root, "build/apps/sfit/sfit")
examples = os.path.join(root, "examples")
RULES = ["paper", "uniform", "chord", "centripetal"]
SETS = [(os.path.join(examples, f), c) for f, c in [
    ("d150_wing.rows", True), ("iea15mw_blade_af50.rows", True),
    ("iea3p4mw_blade_ragged9.rows", True), ("ship_px121_stations.rows", False),
    ("ring_body.rows", True), ("bent_tube.rows", True), ("spout_tube.rows", True),
    ("topobathy.rows", False), ("height_field.rows", False), ("height_field_small.rows", False),
    ("table1_synthetic.rows", False)]]
gen = os.path.join(root, "build", "parameters_sets")
py = "/usr/bin/python3" if os.path.exists("/usr/bin/python3") else sys.executable
subprocess.run([py, os.path.join(root, "bench", "peers", "make_sets.py"), gen,
                "grid", "100000", "ragged", "100000"], check=True, stdout=subprocess.DEVNULL)
SETS += [(os.path.join(gen, "grid_100000.v1.rows"), False),
         (os.path.join(gen, "ragged_100000.v1.rows"), False)]


def fit(path, closed, tol, rule):
    with tempfile.TemporaryDirectory() as d:
        reps = []
        for _ in range(3):
            r = subprocess.run([sfit, "fit", path, "-q", "--report", f"{d}/r.json",
                                "--parameters", rule, "--threads", "1"] + tol
                               + (["--closed", "u"] if closed else []))
            if r.returncode:
                return f"exit {r.returncode}"
            reps.append(json.load(open(f"{d}/r.json")))
        reps.sort(key=lambda r: r["seconds"])
        j = reps[1]
    nu, nv = j["control_points"]
    fell = "" if j["parameters"] == rule else " -> paper"
    return f"{nu} x {nv}{fell} ({j['seconds'] * 1e3:.1f} ms)"


print("| data set | T | " + " | ".join(RULES) + " |")
print("|---|---|" + "---|" * len(RULES))
for path, closed in SETS:
    name = os.path.basename(path)
    tols = ([("T = 1", ["--tol", "1"]), ("T = 10", ["--tol", "10"])] if "table1" in name else
            [(f"{t} diag", ["--tol-rel", t]) for t in ("1e-2", "1e-3", "1e-4")])
    for label, tol in tols:
        cells = [fit(path, closed, tol, rule) for rule in RULES]
        print(f"| {name}{' (closed u)' if closed else ''} | {label} | " + " | ".join(cells) + " |",
              flush=True)
