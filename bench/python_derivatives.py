#!/usr/bin/env python3
"""Evaluation and first derivatives of 10^6 points: sfit against SciPy, in the same run.

    PYTHONPATH=build/python /usr/bin/python3 bench/python_derivatives.py [--size 300]

A height grid (bench/python_overhead.py's terrain, --size^2 points) is fitted by sfit; the
z-coordinate spline of the surface (same knots, same coefficients) is put into SciPy's
RectBivariateSpline, so both evaluate the same function at the same 10^6 random (u, v). sfit
evaluates x, y and z (3 components): it is compared with SciPy's z alone and with three
SciPy splines (x, y, z), what a SciPy user needs for a 3D surface. Printed: best CPU time of
--repeat runs and the ratios sfit / SciPy (below 1: sfit faster). The values are checked
equal (z) to 1e-9 of the data's size. One thread for sfit (SciPy has one), then all cores.
Speed is measured here, never asserted in a test.
"""

import argparse
import os
import time

import numpy as np
from scipy.interpolate import RectBivariateSpline

import sfit


def terrain_grid(m, n):
    s = np.arange(n) / (n - 1)
    t = np.arange(m) / (m - 1)
    S, T = np.meshgrid(s, t)
    z = 10 * np.sin(3 * S) * np.cos(2 * T) + 5 * S * T * T + 0.5 * np.sin(17 * S + 11 * T)
    return np.stack([100 * S, 100 * T, z], axis=-1)


def best(f, repeat):
    wall, cpu, value = [], [], None
    for _ in range(repeat):
        t, c = time.perf_counter(), time.process_time()
        value = f()
        wall.append(time.perf_counter() - t)
        cpu.append(time.process_time() - c)
    return min(wall), min(cpu), value


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--size", type=int, default=300)
    p.add_argument("--tol-rel", type=float, default=1e-4)
    p.add_argument("--points", type=int, default=10**6)
    p.add_argument("--repeat", type=int, default=5)
    a = p.parse_args()

    s = sfit.fit(terrain_grid(a.size, a.size), tol_rel=a.tol_rel).surface
    assert not any(s.periodic)
    # SciPy's spline of z with sfit's knots and coefficients (RectBivariateSpline evaluates
    # self.tck with self.degrees; x is sfit's u, y its v).
    def spline(axis):
        r = RectBivariateSpline(np.arange(5.0), np.arange(5.0), np.zeros((5, 5)))
        r.tck = (s.knots_u, s.knots_v, np.ascontiguousarray(s.control_points[:, :, axis]).ravel())
        r.degrees = (s.degree_u, s.degree_v)
        return r

    xyz = [spline(k) for k in range(3)]  # a SciPy user's 3D surface: one spline per axis
    rbs = xyz[2]

    rng = np.random.default_rng(1)
    u = rng.uniform(0, s.u_end, a.points)
    v = rng.uniform(0, s.v_end, a.points)
    scale = 1e-9 * 100
    print(f"surface {s.count[0]} x {s.count[1]} control points, degree {s.degree}; "
          f"{a.points} random (u, v); load average {os.getloadavg()[0]:.1f}")

    def three(**kw):
        return lambda: [r.ev(u, v, **kw) for r in xyz]

    cases = [
        ("value", lambda t: s(u, v, threads=t), lambda: rbs.ev(u, v), three(),
         lambda mine, ref: np.abs(mine[:, 2] - ref).max()),
        ("d/du", lambda t: s.derivative(u, v, 1, 0, threads=t), lambda: rbs.ev(u, v, dx=1),
         three(dx=1),
         lambda mine, ref: np.abs(mine[:, 2] - ref).max()),
        ("d/dv", lambda t: s.derivative(u, v, 0, 1, threads=t), lambda: rbs.ev(u, v, dy=1),
         three(dy=1),
         lambda mine, ref: np.abs(mine[:, 2] - ref).max()),
        ("value + d/du + d/dv", lambda t: s.derivatives(u, v, order=1, threads=t),
         lambda: (rbs.ev(u, v), rbs.ev(u, v, dx=1), rbs.ev(u, v, dy=1)),
         lambda: (three()(), three(dx=1)(), three(dy=1)()),
         lambda mine, ref: max(np.abs(mine[:, k, 2] - ref[k]).max() for k in range(3))),
        ("normal (vs SciPy d/du + d/dv)", lambda t: s.normal(u, v, threads=t),
         lambda: (rbs.ev(u, v, dx=1), rbs.ev(u, v, dy=1)),
         lambda: (three(dx=1)(), three(dy=1)()), None),
    ]
    print("CPU times, one thread; ratio = sfit / SciPy (z: one SciPy spline, xyz: three, one per axis,")
    print("as sfit evaluates x, y and z); last column: sfit on all cores, wall time")
    print(f"{'':30s} {'SciPy z':>9s} {'SciPy xyz':>10s} {'sfit':>9s} {'/z':>5s} {'/xyz':>5s} "
          f"{'sfit all':>9s}")
    for name, mine, theirs, theirs3, check in cases:
        w_ref, c_ref, ref = best(theirs, a.repeat)
        _, c3, _ = best(theirs3, a.repeat)
        w1, c1, got = best(lambda: mine(1), a.repeat)
        w0, _, _ = best(lambda: mine(0), a.repeat)
        if check is not None:
            err = check(got, ref)
            assert err <= scale * max(1.0, np.abs(got).max() / 100), (name, err)
        print(f"{name:30s} {c_ref * 1e3:7.1f}ms {c3 * 1e3:8.1f}ms {c1 * 1e3:7.1f}ms "
              f"{c1 / c_ref:5.2f} {c1 / c3:5.2f} {w0 * 1e3:7.1f}ms")


if __name__ == "__main__":
    main()
