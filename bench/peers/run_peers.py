#!/usr/bin/env python3
"""Drives the peer benchmark: every tool on every data set and tolerance, in one run.

  run_peers.py --bin build-peers/bench/peers/sfit_peers --out build-peers/peers
               [--max-points 1e7] [--cap 60] [--repeats 5] [--budget 10] [--only NAME,...]
               [--scan-dir DIR]

Data: the data sets of examples/ (table1_synthetic.rows at T = 1 and 10 mm),
and generated grids and ragged sets of 10^2 ... 10^7 points (make_sets.py, cached in OUT/data).
With --scan-dir, also the generated cases of bench/scan_cases.py (the kinds of data users bring,
written to DIR by write_scan_cases.py): the height fields among them (every point z = f(x, y),
rows clipped, with holes or uneven) also go to SciPy's scattered fitter (scipy-scattered,
scipy_scattered_peer.py), and OUT/counts.md compares sfit's count with the best peer within T.
Tolerance: 1e-2 and 1e-3 of the bounding-box diagonal (the same T for every tool), bicubic.
Each tool runs in its own process (sfit_peers fit / scipy_peer.py), which times the fit alone
(median of up to --repeats runs within --budget seconds) and checks the result with the common
closest-point checker. A tool whose single fit is predicted (from the two smaller sizes of the
same series) to exceed --cap seconds is skipped and shown as "skipped (est. > cap)"; a process
killed at its time limit is shown as "timed out".
Writes OUT/results.json, OUT/table.md (also printed) and OUT/time_vs_points.png.
"""
import argparse
import json
import math
import os
import platform
import re
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
EXAMPLES = os.path.join(ROOT, "examples")
DATA_SETS = [  # (file, kind)
    ("height_field_small.rows", "grid"), ("height_field.rows", "grid"), ("topobathy.rows", "grid"),
    ("ship_px121_stations.rows", "ragged"), ("d150_wing.rows", "ragged"),
    ("spout_tube.rows", "ragged"), ("bent_tube.rows", "ragged"),
    ("ring_body.rows", "ragged"), ("iea3p4mw_blade_ragged9.rows", "ragged"),
    ("iea15mw_blade_af50.rows", "ragged"),
]
GRID_PEERS = ["sfit", "sfit-chord", "sfit-mt", "scipy-grid", "sisl-grid", "occt-grid"]
RAGGED_PEERS = ["sfit", "sfit-chord", "sfit-mt", "occt-loft"]
# bench/scan_cases.py's cases (name -> (height field: z = f(x, y) at every point, closed rows)).
SCAN_CASES = {"range_image_holes": (True, False), "terrain_grid_1e5": (True, False),
              "clipped_scan_lines": (True, False), "uneven_rows": (True, False),
              "cornered_sections": (False, False), "lidar_corner_strip": (True, False),
              "lidar_tile": (True, False), "far_offset": (True, False),
              "closed_contours": (False, True), "shaky_closed": (False, True)}
LABEL = {"sfit": "sfit (1 thread)", "sfit-chord": "sfit --parameters chord (1 thread)",
         "sfit-mt": "sfit (2 threads)", "scipy-grid":
         "SciPy RectBivariateSpline", "sisl-grid": "SISL s1966", "occt-grid":
         "OCCT PointsToBSplineSurface", "occt-loft": "OCCT PointsToBSpline + AppSurf",
         "scipy-scattered": "SciPy scattered (LSQ/SmoothBivariateSpline)"}
PEER_OF_SFIT = "sfit"  # the sfit time the ratios are taken against (single thread, as the peers)


def closed_u(path):
    with open(path, errors="replace") as f:
        for line in f:
            if not line.startswith("#"):
                break
            if re.search(r"rows are CLOSED", line, re.I):
                return True
    return False


def run_json(cmd, timeout):
    t0 = time.time()
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return {"error": f"timed out (> {timeout:.0f} s)", "timed_out": True}
    lines = [l for l in p.stdout.splitlines() if l.startswith("{")]
    if not lines:
        return {"error": (p.stderr.strip().splitlines() or ["no output"])[-1][:200]}
    r = json.loads(lines[-1])
    r["wall_s"] = time.time() - t0
    return r


def run_peer(args, peer, path, tol, closed):
    if peer in ("scipy-grid", "scipy-scattered"):
        surf = os.path.join(args.out, "scipy_surface.json")
        script = "scipy_peer.py" if peer == "scipy-grid" else "scipy_scattered_peer.py"
        extra = [] if peer == "scipy-grid" else ["--time-limit", str(args.cap)]
        r = run_json([args.python, os.path.join(HERE, script), path, repr(tol), surf,
                      "--repeats", str(args.repeats), "--budget", str(args.budget)] + extra,
                     args.timeout)
        if "error" not in r:
            c = run_json([args.bin, "check", "--surface", surf, "--data", path, "--tol", repr(tol)],
                         args.timeout)
            r["check"] = c.get("check", {"error": c.get("error")})
        return r
    cmd = [args.bin, "fit", "--peer", peer, "--data", path, "--tol", repr(tol), "--repeats",
           str(args.repeats), "--budget", str(args.budget)]
    if closed:
        cmd.append("--closed-u")
    return run_json(cmd, args.timeout)


def predicted(history, n):
    """Single-fit time predicted at n points from the last two (points, seconds) measured."""
    if not history:
        return 0.0
    n1, t1 = history[-1]
    slope = 1.0
    if len(history) >= 2:
        n0, t0 = history[-2]
        if t0 > 0 and t1 > 0 and n1 > n0:
            slope = max(1.0, math.log(t1 / t0) / math.log(n1 / n0))
    return t1 * (n / n1) ** slope


def fmt_time(s):
    if s is None:
        return ""
    if s < 1e-3:
        return f"{s * 1e6:.0f} µs"
    if s < 1:
        return f"{s * 1e3:.3g} ms"
    return f"{s:.3g} s"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--bin", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--python", default=sys.executable)
    ap.add_argument("--max-points", type=float, default=1e7)
    ap.add_argument("--cap", type=float, default=60.0, help="skip a fit predicted to take longer")
    ap.add_argument("--sfit-cap", type=float, default=300.0, help="the same for sfit")
    ap.add_argument("--timeout", type=float, default=900.0, help="limit of one tool's process")
    ap.add_argument("--repeats", type=int, default=11)
    ap.add_argument("--budget", type=float, default=10.0, help="stop repeating after this long")
    ap.add_argument("--only", default="", help="comma-separated data set names to run")
    ap.add_argument("--scan-dir", default="", help="also bench/scan_cases.py's cases, as "
                    "written to this directory by write_scan_cases.py")
    ap.add_argument("--peers", default="", help="comma-separated tools to run (e.g. sfit-chord)")
    ap.add_argument("--merge-into", default="", help="an earlier results.json: this run's rows "
                    "replace its rows of the same data set, tolerance and tool, and the tables "
                    "are made from the merged results")
    ap.add_argument("--tables-from", default="", help="only remake the tables and the plot "
                    "from an earlier results.json")
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    if args.tables_from:
        with open(args.tables_from) as f:
            write_outputs(json.load(f)["results"], args.out)
        return
    data_dir = os.path.join(args.out, "data")

    cases = []  # (name, path, kind, closed, [(tol label, tol)], series, n)
    info_cache = {}

    def info(path):
        if path not in info_cache:
            info_cache[path] = run_json([args.bin, "info", "--data", path], args.timeout)
        return info_cache[path]

    def rel(path):
        d = info(path)["diagonal"]
        return [("1e-2 diag", 1e-2 * d), ("1e-3 diag", 1e-3 * d)]

    for f, kind in DATA_SETS:
        path = os.path.join(EXAMPLES, f)
        cases.append((f[:-5], path, kind, closed_u(path), None, None))
    t1 = os.path.join(ROOT, "examples", "table1_synthetic.rows")
    cases.append(("table1_synthetic", t1, "ragged", False, [("1 mm", 1.0), ("10 mm", 10.0)], None))
    sizes = [n for n in (1e2, 1e3, 1e4, 1e5, 1e6, 1e7) if n <= args.max_points]
    for kind in ("grid", "ragged"):
        gen = [sys.executable if os.path.exists(sys.executable) else "python3",
               os.path.join(HERE, "make_sets.py"), data_dir]
        for n in sizes:
            gen += [kind, str(int(n))]
        subprocess.run(gen, check=True)
        for n in sizes:
            path = os.path.join(data_dir, f"{kind}_{int(n)}.v1.rows")
            cases.append((f"{kind}_{int(n)}", path, kind, False, None, kind))
    scan = {}  # name -> height field
    for name, (height, closed) in SCAN_CASES.items() if args.scan_dir else ():
        path = os.path.join(args.scan_dir, name + ".rows")
        if os.path.exists(path):
            cases.append((name, path, "scan", closed, None, None))
            scan[name] = height
    if args.only:
        keep = set(args.only.split(","))
        cases = [c for c in cases if c[0] in keep]

    results = []
    history = {}  # (series, tol label, peer) -> [(points, single-fit seconds)]
    stopped = set()  # series where a peer timed out: skip it from then on
    started = time.time()
    for name, path, kind, closed, tols, series in cases:
        d = info(path)
        if "error" in d:
            print(f"{name}: {d['error']}", file=sys.stderr)
            continue
        if tols is None:
            tols = rel(path)
        # Closed rows go the lofting way: the grid fitters know no periodic rows (a user would
        # repeat the seam point, which the loft path does).
        peers = GRID_PEERS if d["grid"] and not closed else RAGGED_PEERS
        if scan.get(name):
            peers = peers + ["scipy-scattered"]
        if args.peers:
            peers = [p for p in peers if p in args.peers.split(",")]
        for tlabel, tol in tols:
            for peer in peers:
                key = (series, tlabel, peer)
                row = {"set": name, "points": d["points"], "rows": d["rows"], "grid": d["grid"],
                       "closed_u": closed, "tol_label": tlabel, "tol": tol, "peer": peer,
                       "series": series}
                est = predicted(history.get(key, []), d["points"]) if series else 0.0
                if peer == "sfit-mt" and d["points"] > 1.01e6:
                    row["skipped"] = "not run above 10^6 points (run time)"
                elif series and key in stopped:
                    row["skipped"] = "skipped (smaller size timed out)"
                elif est > (args.sfit_cap if peer.startswith("sfit") else args.cap):
                    cap = args.sfit_cap if peer.startswith("sfit") else args.cap
                    row["skipped"] = f"skipped (est. {est:.0f} s > {cap:.0f} s)"
                else:
                    r = run_peer(args, peer, path, tol, closed)
                    row.update({k: v for k, v in r.items() if k not in ("points", "rows")})
                    if r.get("timed_out") and series:
                        stopped.add(key)
                    if "median_s" in r and series:
                        history.setdefault(key, []).append((d["points"], min(r["times"])))
                results.append(row)
                status = row.get("skipped") or row.get("error") or (
                    f"{fmt_time(row['median_s'])} {row['shape']} "
                    f"max {row['check'].get('max_distance', float('nan')):.3g} "
                    f"out {row['check'].get('out_of_tolerance')}")
                print(f"[{time.time() - started:6.0f} s] {name} {tlabel} {peer}: {status}",
                      file=sys.stderr, flush=True)
                save_results(args, results)

    if args.merge_into:
        with open(args.merge_into) as f:
            old = json.load(f)["results"]
        new = {(r["set"], r["tol_label"], r["peer"]): r for r in results}
        merged = [new.pop((r["set"], r["tol_label"], r["peer"]), r) for r in old]
        results = merged + list(new.values())
        save_results(args, results)
    write_outputs(results, args.out)


def write_text(path, text):
    """Writes through a temporary file and a rename: never a half-written file."""
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        f.write(text)
    os.replace(tmp, path)


def save_results(args, results):
    write_text(os.path.join(args.out, "results.json"),
               json.dumps({"machine": machine(), "args": vars(args), "results": results},
                          indent=1))


def write_outputs(results, out):
    targets = make_targets(results)
    table = make_table(results) + "\n" + targets
    write_text(os.path.join(out, "table.md"), table)
    write_text(os.path.join(out, "summary.md"), make_compact(results) + "\n" + targets)
    counts = make_counts(results)
    write_text(os.path.join(out, "counts.md"), counts)
    print(counts)
    print(table)
    plot(results, os.path.join(out, "time_vs_points.png"))


def machine():
    cpu = ""
    try:
        with open("/proc/cpuinfo") as f:
            cpu = next(l.split(":", 1)[1].strip() for l in f if l.startswith("model name"))
    except (OSError, StopIteration):
        pass
    return {"cpu": cpu, "cores": os.cpu_count(), "load": os.getloadavg(),
            "python": platform.python_version()}


def make_table(results):
    by_case = {}
    for r in results:
        by_case.setdefault((r["set"], r["tol_label"]), []).append(r)
    out = ["| data set | points (rows) | T | tool | fit time (median, runs) | coefficients "
           "(nu x nv) | max closest distance | points > T | time / sfit |",
           "|---|---|---|---|---|---|---|---|---|"]
    targets = []
    for (name, tl), rs in by_case.items():
        sfit = next((r for r in rs if r["peer"] == PEER_OF_SFIT and "median_s" in r), None)
        for r in rs:
            head = (f"| {name}{' (closed u)' if r['closed_u'] else ''} | {r['points']} "
                    f"({r['rows']}) | {tl} ({r['tol']:.3g}) | {LABEL[r['peer']]} |")
            if "median_s" not in r:
                out.append(head + f" {r.get('skipped') or r.get('error')} | | | | |")
                continue
            c = r.get("check", {})
            ratio = f"{r['median_s'] / sfit['median_s']:.3g}" if sfit else ""
            note = f" ({r['notes']})" if r["peer"].startswith("scipy") else ""
            out.append(head + f" {fmt_time(r['median_s'])} ({len(r['times'])}){note} | "
                       f"{r['coefficients']} ({r['shape']}) | {c.get('max_distance', float('nan')):.3g} | "
                       f"{c.get('out_of_tolerance', '?')} | {ratio} |")
    return "\n".join(out) + "\n"


def make_compact(results):
    """One line per data set and tolerance, one column per tool: time, coefficients, max
    closest distance, points out of tolerance."""
    cols = ["sfit", "sfit-chord", "scipy-grid", "sisl-grid", "occt-grid", "occt-loft",
            "scipy-scattered"]
    names = {"sfit": "sfit (1 thread)", "sfit-chord": "sfit chord (1 thread)",
             "scipy-grid": "SciPy", "sisl-grid": "SISL",
             "occt-grid": "OCCT grid", "occt-loft": "OCCT loft",
             "scipy-scattered": "SciPy scattered"}
    by_case = {}
    for r in results:
        by_case.setdefault((r["set"], r["tol_label"]), {})[r["peer"]] = r
    out = ["| data set | points | T | " + " | ".join(names[c] for c in cols) + " |",
           "|---|---|---|" + "---|" * len(cols)]
    for (name, tl), rs in by_case.items():
        any_r = next(iter(rs.values()))
        cells = []
        for c in cols:
            r = rs.get(c)
            if r is None:
                cells.append("n/a")
            elif "median_s" not in r:
                why = r.get("skipped") or r.get("error") or ""
                cells.append("skipped" if why.startswith("skipped") else
                             "timed out" if why.startswith("timed out") else
                             "failed" if why else "")
            else:
                k = r.get("check", {})
                cells.append(f"{fmt_time(r['median_s'])} · {r['coefficients']} · "
                             f"{k.get('max_distance', float('nan')):.3g} · "
                             f"{k.get('out_of_tolerance', '?')}")
        closed = " (closed)" if any_r["closed_u"] else ""
        out.append(f"| {name}{closed} | {any_r['points']} | {tl} ({any_r['tol']:.3g}) | "
                   + " | ".join(cells) + " |")
    return "\n".join(out) + "\n"


def make_counts(results):
    """Control points of sfit's default against the best peer within T (the common checker's
    "points > T" = 0), one line per data set and tolerance."""
    by_case = {}
    for r in results:
        by_case.setdefault((r["set"], r["tol_label"]), {})[r["peer"]] = r
    out = ["| data set | points | T | sfit default (nu x nv) | sfit points > T | best peer within T "
           "| its count (shape) | sfit / best | peers: count, points > T |",
           "|---|---|---|---|---|---|---|---|---|"]

    def ran(r):
        return r is not None and "coefficients" in r and "check" in r

    for (name, tl), rs in by_case.items():
        s = rs.get("sfit")
        any_r = next(iter(rs.values()))
        within = [r for p, r in rs.items() if not p.startswith("sfit") and ran(r)
                  and r["check"].get("out_of_tolerance") == 0]
        best = min(within, key=lambda r: r["coefficients"]) if within else None
        others = []
        for p, r in rs.items():
            if p.startswith("sfit"):
                continue
            if ran(r):
                others.append(f"{LABEL[p]} {r['coefficients']}, "
                              f"{r['check'].get('out_of_tolerance', '?')}")
            else:
                why = (r.get("skipped") or r.get("error") or "failed")[:60]
                others.append(f"{LABEL[p]}: {why}")
        sc = f"{s['coefficients']} ({s['shape']})" if ran(s) else (
            (s or {}).get("error") or (s or {}).get("skipped") or "not run")
        so = s["check"].get("out_of_tolerance", "?") if ran(s) else ""
        ratio = f"{s['coefficients'] / best['coefficients']:.3g}" if ran(s) and best else ""
        out.append(f"| {name} | {any_r['points']} | {tl} ({any_r['tol']:.3g}) | {sc} | {so} | "
                   + (f"{LABEL[best['peer']]} | {best['coefficients']} ({best['shape']}) | "
                      if best else "none | | ") + f"{ratio} | " + "; ".join(others) + " |")
    return "\n".join(out) + "\n"


def make_targets(results):
    """The speed targets against the peers (docs/benchmarks.md), each with the ratio measured
    in this run, for sfit's default and for sfit with chord-length parameters."""
    return "\n".join(make_targets_for(results, p) for p in ("sfit", "sfit-chord"))


def make_targets_for(results, which):
    """The targets table for the sfit variant `which`."""
    by_case = {}
    for r in results:
        by_case.setdefault((r["set"], r["tol_label"]), {})[r["peer"]] = r
    out = [f"Targets for {LABEL[which]}:", "",
           "| target | data set | T | sfit | fastest peer | ratio | OCCT | ratio | "
           "sfit within T | met |", "|---|---|---|---|---|---|---|---|---|---|"]
    for (name, tl), rs in by_case.items():
        sfit = rs.get(which)
        if not sfit or "median_s" not in sfit:
            continue
        held = sfit.get("check", {}).get("out_of_tolerance") == 0
        t = sfit["median_s"]
        if name == "table1_synthetic" and tl == "1 mm":
            occt = rs.get("occt-loft", {})
            ro = occt["median_s"] / t if "median_s" in occt else None
            ok = t < 1e-3 and ro is not None and ro >= 20 and held
            out.append(f"| < 1 ms, OCCT >= 20x | {name} | {tl} | {fmt_time(t)} | | | "
                       f"{fmt_time(occt.get('median_s'))} | {ro:.3g} | {held} | "
                       f"{'yes' if ok else 'NO'} |" if ro else f"| < 1 ms, OCCT >= 20x | {name} "
                       f"| {tl} | {fmt_time(t)} | | | {occt.get('skipped') or occt.get('error')} "
                       f"| | {held} | NO |")
            continue
        if not sfit["grid"] or sfit["closed_u"] or sfit["points"] > 1.01e6:
            continue
        peers = [r for p, r in rs.items() if p in ("scipy-grid", "sisl-grid", "occt-grid")
                 and "median_s" in r]
        fastest = min(peers, key=lambda r: r["median_s"]) if peers else None
        rf = fastest["median_s"] / t if fastest else None
        occt = rs.get("occt-grid", {})
        ro = occt["median_s"] / t if "median_s" in occt else None
        ok = rf is not None and rf >= 10 and (ro is None or ro >= 100) and held
        out.append(f"| fastest peer >= 10x, OCCT >= 100x | {name} | {tl} | {fmt_time(t)} | "
                   + (f"{LABEL[fastest['peer']]} {fmt_time(fastest['median_s'])} | {rf:.3g} | "
                      if fastest else "| | ")
                   + (f"{fmt_time(occt['median_s'])} | {ro:.3g} | " if ro else
                      f"{occt.get('skipped') or occt.get('error')} | | ")
                   + f"{held} | {'yes' if ok else 'NO'} |")
    return "\n".join(out) + "\n"


def plot(results, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 2, figsize=(12, 5), sharey=True)
    for ax, series in zip(axes, ("grid", "ragged")):
        for peer in GRID_PEERS if series == "grid" else RAGGED_PEERS:
            pts = sorted((r["points"], r["median_s"]) for r in results
                         if r["series"] == series and r["peer"] == peer
                         and r["tol_label"] == "1e-3 diag" and "median_s" in r)
            if not pts:
                continue
            xs, ys = zip(*pts)
            label = LABEL[peer]
            if peer.startswith("sfit") and len(pts) >= 3:
                lx, ly = [math.log10(x) for x in xs], [math.log10(y) for y in ys]
                mx, my = sum(lx) / len(lx), sum(ly) / len(ly)
                slope = sum((a - mx) * (b - my) for a, b in zip(lx, ly)) / sum(
                    (a - mx) ** 2 for a in lx)
                label += f" (slope {slope:.2f})"
            ax.loglog(xs, ys, "o-", label=label, lw=2 if peer.startswith("sfit") else 1.2)
            if peer == PEER_OF_SFIT:
                ax.loglog([xs[0], xs[-1]], [ys[0], ys[0] * xs[-1] / xs[0]], "k:", lw=1,
                          label="linear in N (from sfit's first point)")
        ax.set_title(f"generated {series} sets, T = 1e-3 of the box diagonal, bicubic")
        ax.set_xlabel("number of points")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    axes[0].set_ylabel("fit time, median (s)")
    fig.tight_layout()
    fig.savefig(path + ".tmp", dpi=110, format="png")
    os.replace(path + ".tmp", path)


if __name__ == "__main__":
    main()
