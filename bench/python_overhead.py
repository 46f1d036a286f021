#!/usr/bin/env python3
"""Overhead of the Python module over the C++ fit, and the speed of evaluation from Python.

    PYTHONPATH=build/python /usr/bin/python3 bench/python_overhead.py [--cli build/apps/sfit/sfit]

1. Fit of a 10^6-point grid (1000 x 1000 on the terrain of bench/synthetic.h, T = 1e-3 of
   the diagonal): `sfit fit grid.srows --report` (its report's seconds: the C++ fit alone)
   against sfit.fit() from Python (wall time of the call: conversion of the array, the fit,
   the result). The surfaces are checked equal bit for bit. Target: within 5%.
2. Evaluation of 10^6 (u, v) parameters by Surface.__call__ (and the 1000 x 1000 grid).
   Target: under 50 ms.
Best and median of --repeat runs each. Speed is measured here, never asserted in a test.
"""

import argparse
import json
import os
import pathlib
import statistics
import subprocess
import tempfile
import time

import numpy as np

import sfit


def terrain_grid(m, n):
    """bench/synthetic.h grid(M, N): M rows of N points on terrain(s, t) over [0, 100]^2."""
    s = np.arange(n) / (n - 1)
    t = np.arange(m) / (m - 1)
    S, T = np.meshgrid(s, t)
    z = 10 * np.sin(3 * S) * np.cos(2 * T) + 5 * S * T * T + 0.5 * np.sin(17 * S + 11 * T)
    return np.stack([100 * S, 100 * T, z], axis=-1)


def write_srows(path, grid):
    """The binary .srows form (include/sfit/io/rows_binary.h)."""
    m, n, _ = grid.shape
    with open(path, "wb") as f:
        f.write(b"SFITROWS")
        f.write(np.array([1, 0], dtype="<u4").tobytes())
        f.write(np.array([m, m * n], dtype="<u8").tobytes())
        f.write(np.full(m, n, dtype="<u8").tobytes())
        f.write(np.ascontiguousarray(grid, dtype="<f8").tobytes())


CPU = {}


def timed(f, repeat, key=None):
    """Best and median wall time of f() over `repeat` calls (best CPU time into CPU[key])."""
    times, cpu, value = [], [], None
    for _ in range(repeat):
        t, c = time.perf_counter(), time.process_time()
        value = f()
        times.append(time.perf_counter() - t)
        cpu.append(time.process_time() - c)
    if key:
        CPU[key] = min(cpu)
    return min(times), statistics.median(times), value


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--cli", default="build/apps/sfit/sfit")
    p.add_argument("--size", type=int, default=1000, help="grid side (default 1000: 10^6 points)")
    p.add_argument("--tol-rel", type=float, default=1e-3)
    p.add_argument("--threads", type=int, default=0)
    p.add_argument("--repeat", type=int, default=7)
    p.add_argument("--json", help="also write the numbers to this file")
    a = p.parse_args()

    grid = terrain_grid(a.size, a.size)
    out = {"points": grid.shape[0] * grid.shape[1], "tol_rel": a.tol_rel, "threads": a.threads}
    with tempfile.TemporaryDirectory() as tmp:
        tmp = pathlib.Path(tmp)
        write_srows(tmp / "grid.srows", grid)
        cli_seconds = []
        for _ in range(a.repeat):
            subprocess.run([a.cli, "fit", str(tmp / "grid.srows"), "-q", "--tol-rel", str(a.tol_rel),
                            "--threads", str(a.threads), "-o", str(tmp / "cli.json"), "--report",
                            str(tmp / "report.json")], check=True)
            cli_seconds.append(json.loads((tmp / "report.json").read_text())["seconds"])
        cli_surface = json.loads((tmp / "cli.json").read_text())

    inner = []

    def python_fit():
        f = sfit.fit(grid, tol_rel=a.tol_rel, threads=a.threads)
        inner.append(f.report["seconds"])
        return f

    best, median, fit = timed(python_fit, a.repeat)
    same = (np.array_equal(fit.surface.control_points, np.array(cli_surface["control_points"]))
            and np.array_equal(fit.surface.knots_u, cli_surface["knots_u"]))
    out["fit"] = {
        "cli_report_seconds": {"best": min(cli_seconds), "median": statistics.median(cli_seconds)},
        "python_wall_seconds": {"best": best, "median": median},
        "python_report_seconds": {"best": min(inner), "median": statistics.median(inner)},
        "overhead_vs_cli": {"best": best / min(cli_seconds) - 1,
                            "median": median / statistics.median(cli_seconds) - 1},
        "overhead_in_process": {"median": median - statistics.median(inner)},
        "control_points": fit.report["control_points"],
        "same_surface_as_cli": bool(same),
    }

    s = fit.surface
    rng = np.random.default_rng(1)
    u = rng.uniform(0, s.u_end, 10**6)
    v = rng.uniform(0, s.v_end, 10**6)
    ev = {}
    for threads in (a.threads, 1):
        key = f"pointwise_threads_{threads}"
        b, m, _ = timed(lambda: s(u, v, threads=threads), a.repeat, key)
        ev[key] = {"best": b, "median": m, "cpu_best": CPU[key]}
    gu = np.linspace(0, s.u_end, 1000)
    gv = np.linspace(0, s.v_end, 1000)
    key = f"grid_1000x1000_threads_{a.threads}"
    b, m, _ = timed(lambda: s(gu, gv, grid=True, threads=a.threads), a.repeat, key)
    ev[key] = {"best": b, "median": m, "cpu_best": CPU[key]}
    key = f"normal_threads_{a.threads}"
    b, m, _ = timed(lambda: s.normal(u, v, threads=a.threads), a.repeat, key)
    ev[key] = {"best": b, "median": m, "cpu_best": CPU[key]}
    out["evaluate_1e6"] = ev
    out["load_average"] = os.getloadavg()[0]

    f = out["fit"]
    print(f"fit of {out['points']} points, T = {a.tol_rel:g} diag, threads {a.threads}: "
          f"{f['control_points'][0]} x {f['control_points'][1]} control points, same surface as "
          f"the CLI: {'yes' if same else 'NO'}")
    print(f"  C++ fit (CLI report)  best {f['cli_report_seconds']['best'] * 1e3:8.1f} ms  "
          f"median {f['cli_report_seconds']['median'] * 1e3:8.1f} ms")
    print(f"  sfit.fit() wall       best {best * 1e3:8.1f} ms  median {median * 1e3:8.1f} ms  "
          f"(overhead {100 * f['overhead_vs_cli']['best']:+.1f}% best, "
          f"{100 * f['overhead_vs_cli']['median']:+.1f}% median; in-process "
          f"{f['overhead_in_process']['median'] * 1e3:.1f} ms)")
    print(f"  C++ fit in sfit.fit() best {min(inner) * 1e3:8.1f} ms (its report's seconds)")
    for k, t in ev.items():
        print(f"  evaluate 10^6 {k:28s} best {t['best'] * 1e3:7.1f} ms  median "
              f"{t['median'] * 1e3:7.1f} ms  (CPU {t['cpu_best'] * 1e3:.1f} ms)")
    print(f"  load average {out['load_average']:.1f}")
    if a.json:
        pathlib.Path(a.json).write_text(json.dumps(out, indent=2) + "\n")


if __name__ == "__main__":
    main()
