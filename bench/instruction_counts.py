#!/usr/bin/python3
"""Instructions of the default (--method surface) and of the two stages (--method sfit01) on
every example set at 1e-2, 1e-3 and 1e-4 of its diagonal, counted by valgrind's callgrind inside
sfit::fit_surface() only (no start-up, reading or writing), one thread: deterministic, so two
binaries compare on a loaded machine where wall times move by 2x.

    bench/instruction_counts.py SFIT [--before SFIT_BEFORE] [--sets NAME ...]

Prints a Markdown table: the default's nu x nv and instructions (and the before binary's, with
the ratio after / before, where --before is given), the two stages' instructions and the ratio
default / sfit01. A before binary's surfaces are compared too: "same" where the surface JSON
(control points, knots, degrees) is identical. Closed flags as bench/method_ratio.py states
them. Takes a few minutes (callgrind runs 50-100x slower than the fit).
"""
import argparse
import hashlib
import json
import os
import re
import subprocess
import tempfile

root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CLOSED_U = {"d150_wing.rows", "iea15mw_blade_af50.rows", "iea3p4mw_blade_ragged9.rows",
            "ring_body.rows", "bent_tube.rows", "spout_tube.rows", "teapot_body.rows",
            "teapot_handle.rows", "teapot_spout_small.rows"}


def count(sfit, path, rel, method):
    """(instructions, 'nu x nv', sha256 of the surface without its report) of one fit."""
    with tempfile.TemporaryDirectory() as d:
        cmd = ["valgrind", "--tool=callgrind", "--toggle-collect=sfit::fit_surface(*",
               f"--callgrind-out-file={d}/cg", sfit, "fit", path, "-q", "--tol-rel", rel,
               "--threads", "1", "--method", method, "-o", f"{d}/s.json"]
        if os.path.basename(path) in CLOSED_U:
            cmd += ["--closed", "u"]
        p = subprocess.run(cmd, capture_output=True, text=True, check=True)
        ir = int(re.search(r"Collected : (\d+)", p.stderr).group(1))
        with open(f"{d}/s.json") as f:
            s = json.load(f)
        report = s.pop("report", {})
        h = hashlib.sha256(json.dumps(s, sort_keys=True).encode()).hexdigest()
        return ir, "x".join(str(c) for c in report["control_points"]), h


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("sfit")
    ap.add_argument("--before")
    ap.add_argument("--sets", nargs="*")
    a = ap.parse_args()
    names = sorted(n for n in os.listdir(os.path.join(root, "examples")) if n.endswith(".rows"))
    if a.sets:
        names = [n for n in names if n in a.sets or n[:-5] in a.sets]
    head = "| data set | tolerance | default nu x nv | default Minstr |"
    if a.before:
        head += " before nu x nv | before Minstr | after / before | surface |"
    head += " sfit01 Minstr | default / sfit01 |"
    print(head)
    print("|" + "---|" * (head.count("|") - 1))
    total = [0, 0, 0]
    worst = 0.0
    for name in names:
        path = os.path.join(root, "examples", name)
        for rel in ("1e-2", "1e-3", "1e-4"):
            ir, cp, h = count(a.sfit, path, rel, "surface")
            base, _, _ = count(a.sfit, path, rel, "sfit01")
            row = f"| {name} | {rel} diag | {cp} | {ir / 1e6:.1f} |"
            if a.before:
                bir, bcp, bh = count(a.before, path, rel, "surface")
                total[1] += bir
                row += (f" {bcp} | {bir / 1e6:.1f} | {ir / bir:.2f} | "
                        f"{'same' if bh == h else 'differs'} |")
            total[0] += ir
            total[2] += base
            worst = max(worst, ir / base)
            row += f" {base / 1e6:.1f} | {ir / base:.2f} |"
            print(row, flush=True)
    line = f"| all | | | {total[0] / 1e6:.0f} |"
    if a.before:
        line += f" | {total[1] / 1e6:.0f} | {total[0] / total[1]:.2f} | |"
    line += f" {total[2] / 1e6:.0f} | {total[0] / total[2]:.2f} |"
    print(line)
    print(f"\nLargest ratio default / sfit01 (instructions): {worst:.2f} (target: at most 1.5)")


if __name__ == "__main__":
    main()
