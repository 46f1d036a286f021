#!/usr/bin/env python3
"""sfit.dask on a LocalCluster of this machine against the in-memory fit (docs/python.md,
"More than one machine").

Generates --points points of a smooth field in ragged rows on the workers (each chunk made by
the worker that computes it; the client never holds them), fits one surface with
sfit.dask.fit (count search included), and reports the wall time, the rounds, the peak memory
of every worker process and of the client. Then, in the same run, the in-memory fit of
--reference points of the same field at the counts found (sfit.dask.in_memory_fit, the
library's fixed-counts fit), its time and the client's peak after it, and the distributed fit
of those --reference points at the same counts, which must equal it to 1e-10 relative.

    PYTHONPATH=build/python /usr/bin/python3 bench/dask_fit.py --points 1e8 --reference 1e7
    PYTHONPATH=build/python /usr/bin/python3 bench/dask_fit.py --points 1e7 --reference 1e6
    PYTHONPATH=build/python /usr/bin/python3 bench/dask_fit.py --points 1e7 --reference 1e7 \
        --parameters geometric

Memory per worker: the peak resident set of each worker process (getrusage, run on the
workers); the client's: the peak of this process (VmHWM) before and after the in-memory fit.
Time: wall and CPU (each worker's, the client's with the scheduler it runs), every pass of the
fit (report["passes"]: what, row step, seconds), the median full pass; the load average
before and after, since the machine may be shared. The LocalCluster's workers start without
Dask's MALLOC_TRIM_THRESHOLD_ (--dask-malloc-trim keeps it; docs/python.md says why).
10^8 points took 73.5 s at a load of 4 on 2 cores, 82-123 s of worker CPU (docs/python.md,
"More than one machine").
"""

import argparse
import json
import os
import math
import resource
import time

import numpy as np


def layout(n_points, seed=11):
    """Row sizes of a ragged scan of about n_points: sqrt(n) rows, each 0.6 ... 1.4 sqrt(n)
    points (a deterministic function of the row)."""
    m = max(4, int(math.sqrt(n_points)))
    j = np.arange(m)
    w = 1.0 + 0.4 * np.sin(0.37 * j + seed) * np.cos(0.011 * j)
    sizes = np.maximum(4, np.floor(w * n_points / w.sum())).astype(np.int64)
    sizes[-1] += n_points - sizes.sum()
    return sizes


def generate(g0, g1, first_row, starts, sizes, rows):
    """Points g0 ... g1-1 of the scan (x, y, z, row): row j at y_j, its points unevenly along
    x, z a smooth field. A function of the point's row and index only, so any chunking of the
    same scan gives the same points."""
    g = np.arange(g0, g1)
    r = np.searchsorted(starts, g, side="right") - 1
    j = (r + first_row).astype(float)
    k = (g - starts[r]).astype(float)
    n = sizes[r].astype(float)
    x = (k + 0.3 * np.sin(12.9898 * k + 78.233 * j)) / (n - 1)
    x = np.where(k == 0, 0.0, np.where(k == n - 1, 1.0, x))
    y = j / (rows - 1) + 0.2 / rows * np.sin(7.1 * j) + 0.01 * np.sin(5 * x)
    z = 0.2 * np.sin(3 * x + 1) * np.cos(2.5 * y) + 0.1 * x * y * y + 0.02 * np.sin(9 * x * y)
    return np.column_stack([x, y, z, j])


def scan(n_points, chunk_points):
    """The scan as a dask array (n, 4), each chunk generated on a worker."""
    import dask
    import dask.array as da

    sizes = layout(n_points)
    starts = np.concatenate([[0], np.cumsum(sizes)])
    blocks = []
    for g0 in range(0, n_points, chunk_points):
        g1 = min(n_points, g0 + chunk_points)
        r0 = int(np.searchsorted(starts, g0, side="right") - 1)
        r1 = int(np.searchsorted(starts, g1 - 1, side="right"))
        blocks.append(da.from_delayed(
            dask.delayed(generate, pure=True)(g0, g1, r0, starts[r0:r1], sizes[r0:r1],
                                              len(sizes)), shape=(g1 - g0, 4), dtype=float))
    return da.concatenate(blocks), sizes


def peak_mb():
    """This process's peak resident memory (VmHWM), MB."""
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith("VmHWM:"):
                return int(line.split()[1]) / 1024
    return float("nan")


def worker_peak_mb():
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


def cpu_seconds():
    """This process's CPU time (user + system), s: steadier than wall on a shared machine."""
    r = resource.getrusage(resource.RUSAGE_SELF)
    return r.ru_utime + r.ru_stime


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--points", type=float, default=1e8)
    p.add_argument("--reference", type=float, default=1e7, help="points of the in-memory fit")
    p.add_argument("--chunk-points", type=float, default=2e6)
    p.add_argument("--tol-rel", type=float, default=1e-3)
    p.add_argument("--parameters", default="uniform", choices=["uniform", "paper", "geometric"],
                   help="the parameter rule (geometric: each point's (u, v) from a base plane, "
                   "corrected by projection; the per-point parameters stay on the workers)")
    p.add_argument("--counts", help="NU,NV: fit at these counts (one round, no search)")
    p.add_argument("--workers", type=int, default=2)
    p.add_argument("--memory-limit", default="2GB", help="per worker")
    p.add_argument("--threads", action="store_true",
                   help="one worker process with --workers threads instead of --workers "
                   "processes of one thread (sfit's chunk work runs without the GIL)")
    p.add_argument("--scheduler", help="address of a running scheduler instead of a LocalCluster")
    p.add_argument("--dask-malloc-trim", action="store_true",
                   help="keep Dask's MALLOC_TRIM_THRESHOLD_=65536 in the workers (it turns off "
                   "glibc's adaptive mmap threshold: every large numpy temporary is mapped and "
                   "zeroed afresh, the generator 2.5 times slower)")
    p.add_argument("--json", help="write the numbers here too")
    a = p.parse_args(argv)

    from distributed import Client, LocalCluster

    import sfit
    import sfit.dask

    n, ref, chunk = int(a.points), int(a.reference), int(a.chunk_points)
    cluster = None
    if a.scheduler:
        client = Client(a.scheduler)
    else:
        import dask

        env = dict(dask.config.get("distributed.nanny.pre-spawn-environ"))
        if not a.dask_malloc_trim:
            env.pop("MALLOC_TRIM_THRESHOLD_", None)
        dask.config.set({"distributed.nanny.pre-spawn-environ": env})
        cluster = LocalCluster(n_workers=1 if a.threads else a.workers,
                               threads_per_worker=a.workers if a.threads else 1, processes=True,
                               memory_limit=a.memory_limit, dashboard_address=":0")
        client = Client(cluster)
    out = {"points": n, "reference": ref, "parameters": a.parameters, "chunk_points": chunk,
           "workers": a.workers,
           "threads_in_one_worker": a.threads,
           "memory_limit_per_worker": a.memory_limit, "load_before": os.getloadavg()}
    try:
        x, sizes = scan(n, chunk)
        cpu0 = client.run(cpu_seconds)
        client_cpu0 = cpu_seconds()
        t = time.perf_counter()
        counts = None if a.counts is None else [int(c) for c in a.counts.split(",")]
        f = sfit.dask.fit(x, tol_rel=a.tol_rel, parameters=a.parameters, counts=counts)
        out["dask_seconds"] = time.perf_counter() - t
        out["client_cpu_seconds"] = cpu_seconds() - client_cpu0
        cpu1 = client.run(cpu_seconds)
        out["worker_cpu_seconds"] = sorted(cpu1[w] - cpu0[w] for w in cpu1)
        r = f.report
        out.update(rows=len(sizes), chunks=r["chunks"], counts=r["control_points"],
                   rounds=r["pairs_tried"], rows_step=r["rows_step"],
                   full_passes=r["full_passes"], stop_reason=r["stop_reason"],
                   within_tolerance=r["within_tolerance"],
                   max_deviation=r["max_deviation"], tolerance=r["tolerance"],
                   partial_bytes=r["partial_bytes"], passes=r["passes"])
        full = [q["seconds"] for q in r["passes"] if q["rows_step"] == 1]
        out["seconds_per_full_pass"] = {"median": float(np.median(full)), "max": max(full)}
        out["seconds_on_the_sample"] = sum(q["seconds"] for q in r["passes"]
                                           if q["rows_step"] > 1)
        out["load_after_dask"] = os.getloadavg()
        out["worker_peak_mb"] = sorted(client.run(worker_peak_mb).values())
        out["client_peak_mb_after_dask"] = peak_mb()

        # The in-memory fit of `ref` points of the same kind of scan, at the same counts.
        xr, _ = scan(ref, chunk)
        t = time.perf_counter()
        pts = xr.compute(scheduler="sync")
        cut = np.flatnonzero(np.diff(pts[:, 3])) + 1
        rows = [q[:, :3] for q in np.split(pts, cut)]
        del pts
        out["reference_generate_seconds"] = time.perf_counter() - t
        t = time.perf_counter()
        cpu = cpu_seconds()
        mem = sfit.dask.in_memory_fit(rows, r["control_points"], tol=r["tolerance"],
                                      parameters=a.parameters)
        out["in_memory_within_tolerance"] = mem.report["within_tolerance"]
        out["in_memory_seconds"] = time.perf_counter() - t
        out["in_memory_cpu_seconds"] = cpu_seconds() - cpu
        out["client_peak_mb_after_in_memory"] = peak_mb()
        t = time.perf_counter()
        same = sfit.dask.fit(xr, tol=r["tolerance"], counts=r["control_points"],
                             parameters=a.parameters)
        out["dask_reference_passes"] = same.report["full_passes"]
        out["dask_reference_one_round_seconds"] = time.perf_counter() - t
        out["reference_relative_difference"] = float(
            np.max(np.abs(same.surface.control_points - mem.surface.control_points)) /
            np.max(np.abs(mem.surface.control_points)))
        out["seconds_per_1e6_points_per_full_pass"] = \
            out["seconds_per_full_pass"]["median"] / (n / 1e6)
        out["load_after"] = os.getloadavg()
    finally:
        client.close()
        if cluster is not None:
            cluster.close()
    print(json.dumps(out, indent=1))
    if a.json:
        with open(a.json, "w") as f:
            json.dump(out, f, indent=1)
    return 0 if out["reference_relative_difference"] < 1e-10 and out["within_tolerance"] else 1


if __name__ == "__main__":
    raise SystemExit(main())
