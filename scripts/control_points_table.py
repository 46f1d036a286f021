#!/usr/bin/python3
"""Control points and time of the default method (the surface search) against --method sfit01
on every .rows file given, at fractions of the bounding-box diagonal, beside the best peer
within T; the Markdown table for docs/control-points.md and the README.

    scripts/control_points_table.py --sfit build/apps/sfit/sfit examples/*.rows
    scripts/control_points_table.py --generated /tmp/gen examples/*.rows   # + smooth grids
    scripts/control_points_table.py --checker build-peers/bench/peers/sfit_peers examples/*.rows

Closed rows are read from each file's header (a line saying the rows are CLOSED). With
--generated DIR the script also writes and measures a DEM-like height field of 10^5 points
and a wavy closed cylinder into DIR. Peers (OpenCASCADE, SISL, SciPy) are measured by
bench/peers/run_peers.py; the best one within T per data set and T is read from its full
table (--peers-table, default docs/bench_peers.md). --checker runs the peer benchmark's
closest-point checker on the default's surface (the "points > T" column). Times are the
least CPU time of --repeats whole CLI runs on one thread (start-up and reading included).
"""
import argparse
import json
import os
import re
import resource
import subprocess
import sys
import tempfile
import time

# Closed rows are told as the peer benchmark tells them (a header line "rows are CLOSED").
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "bench",
                                "peers"))
from run_peers import ROOT, closed_u  # noqa: E402


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


def cpu_seconds():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def fit(sfit, path, frac, closed, method, repeats, checker=None):
    """One sfit fit run `repeats` times (the least CPU time kept: the whole CLI run, one
    thread); with `checker` (the peer benchmark's sfit_peers) the same fit is made and checked
    by its closest-point checker too."""
    with tempfile.TemporaryDirectory() as d:
        rep = os.path.join(d, "r.json")
        cmd = [sfit, "fit", path, "--tol-rel", str(frac), "--method", method, "--report", rep,
               "--threads", "1", "-q"]
        if closed:
            cmd += ["--closed", "u"]
        best = None
        for _ in range(repeats):
            c0 = cpu_seconds()
            p = subprocess.run(cmd, capture_output=True, text=True)
            cpu = cpu_seconds() - c0
            if p.returncode != 0:
                return None
            best = cpu if best is None else min(best, cpu)
        r = json.load(open(rep))
        nu, nv = r["control_points"]
        out = {"nu": nu, "nv": nv, "cpu": best, "fit_s": r["seconds"],
               "within": r["within_tolerance"], "parameters": r["parameters"],
               "stop": r.get("stop_reason", ""), "method": r.get("method", method),
               "pairs": r.get("pairs_tried", 0),
               # The knot rule, where the report names one (uniform knots before it did).
               "knots": r.get("knots", "uniform") if isinstance(r.get("knots", "uniform"), str)
               else "uniform"}
        if checker:
            # The same default fit in the peer benchmark's process (docs/bench_peers.md), its
            # surface checked there by closest-point distances.
            cmd = [checker, "fit", "--peer", "sfit", "--data", path, "--tol",
                   repr(r["tolerance"][0]), "--repeats", "1", "--budget", "0"]
            if closed:
                cmd.append("--closed-u")
            c = subprocess.run(cmd, capture_output=True, text=True)
            lines = [l for l in c.stdout.splitlines() if l.startswith("{")]
            res = json.loads(lines[-1]) if lines else {}
            out["check"] = res.get("check", {})
            if res.get("coefficients") not in (None, nu * nv):
                out["check"] = {"out_of_tolerance": f"(other fit: {res.get('coefficients')})"}
        return out


def best_peers(table):
    """The fewest coefficients of any peer (not sfit) with no point beyond T, per (data set,
    T / diag), from the peer benchmark's full table (docs/bench_peers.md)."""
    best = {}
    if not table or not os.path.exists(table):
        return best
    for line in open(table):
        c = [x.strip() for x in line.split("|")]
        if len(c) < 10 or not re.match(r"1e-\d diag", c[3]):
            continue
        name, frac, tool, coef, over = (c[1].replace(" (closed u)", ""), float(c[3].split()[0]),
                                        c[4], c[6], c[8])
        m = re.match(r"(\d+)", coef)
        if tool.startswith("sfit") or not m or over != "0":
            continue
        k = (name, frac)
        if k not in best or int(m.group(1)) < best[k][0]:
            best[k] = (int(m.group(1)), tool.split()[0])
    return best


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("files", nargs="*")
    ap.add_argument("--sfit", default="build/apps/sfit/sfit")
    ap.add_argument("--fractions", default="1e-2,1e-3")
    ap.add_argument("--generated", help="folder to write the generated smooth sets into")
    ap.add_argument("--peers-table", default=os.path.join(ROOT, "docs", "bench_peers.md"),
                    help="the peer benchmark's full table, for the best peer within T")
    ap.add_argument("--checker", help="the peer benchmark's sfit_peers, to check the default's "
                    "surface by closest-point distances")
    ap.add_argument("--repeats", type=int, default=3)
    a = ap.parse_args()
    files = list(a.files)
    if a.generated:
        files += generate(a.generated)
    peers = best_peers(a.peers_table)
    print(f"Load average at start: {open('/proc/loadavg').read().split()[0]}.\n")
    print("| data | T / diag | default nu x nv | rule | knots | sfit01 nu x nv | best peer within T | "
          "default / peer | points > T (checker) | CPU s default / sfit01 | ratio |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    ratios, times = [], []
    for path in files:
        closed = closed_u(path)
        name = re.sub(r"(\.v\d+)?\.rows$", "", os.path.basename(path))
        for label in a.fractions.split(","):
            frac = float(label)
            d = fit(a.sfit, path, frac, closed, "surface", a.repeats, a.checker)
            s = fit(a.sfit, path, frac, closed, "sfit01", a.repeats)
            if not d or not s:
                print(f"| {name} | {label} | failed | | | | | | | | |")
                continue
            nd, ns = d["nu"] * d["nv"], s["nu"] * s["nv"]
            rule = d["parameters"] if d["method"] == "surface" else "(sfit01's)"
            if "the rows took all of T" in d["stop"]:
                rule = "(sfit01's, rows at T)"
            peer = peers.get((name, frac))
            vs = ""
            if peer:
                ratios.append(nd / peer[0])
                vs = f"{nd / peer[0]:.2f}"
            check = d.get("check", {}).get("out_of_tolerance", "")
            times.append(d["cpu"] / s["cpu"])
            print(f"| {name} | {label} | {d['nu']} x {d['nv']} = {nd} | {rule} | {d['knots']} | "
                  f"{s['nu']} x {s['nv']} = {ns} | "
                  f"{f'{peer[0]} ({peer[1]})' if peer else '-'} | {vs} | {check} | "
                  f"{d['cpu']:.3f} / {s['cpu']:.3f} | {d['cpu'] / s['cpu']:.1f} |")
            sys.stdout.flush()
    if ratios:
        ratios.sort()
        print(f"\nAgainst the best peer within T: {len(ratios)} cases, median "
              f"{ratios[len(ratios) // 2]:.2f}x, worst {ratios[-1]:.2f}x, "
              f"{sum(r <= 1 for r in ratios)} at or below it.")
    if times:
        print(f"CPU time of the whole CLI run, default over sfit01: at most {max(times):.1f}x.")


if __name__ == "__main__":
    main()
