#!/usr/bin/env python3
"""Fits a data set with sfit and plots the surface and the deviation of every point.

    /usr/bin/python3 examples/python/plot_fit.py examples/d150_wing.rows --closed u -o wing.png

Left: the fitted surface (evaluated on a grid) with the data points; right: each point's
largest per-axis deviation |S(u, v) - D| as a fraction of the tolerance T, by row (1.0 is
the bound sfit guarantees). Needs numpy and matplotlib (Debian python3-matplotlib); uses
matplotlib's Agg backend, so no display is needed.
"""

import argparse

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import sfit  # noqa: E402


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("rows", help="rows of points: any input `sfit fit` reads")
    p.add_argument("-o", "--out", required=True, help="PNG file to write")
    p.add_argument("--closed", default="", help="'', 'u', 'v' or 'uv'")
    p.add_argument("--tol-rel", type=float, default=None, help="tolerance as a fraction of the diagonal")
    p.add_argument("--samples", type=int, default=60, help="grid samples per direction")
    a = p.parse_args(argv)

    fit = sfit.fit(sfit.load_rows(a.rows), closed=a.closed, tol_rel=a.tol_rel)
    s, r = fit.surface, fit.report
    u = np.linspace(0, s.u_end, a.samples + (1 if s.periodic[0] else 0))
    v = np.linspace(0, s.v_end, a.samples + (1 if s.periodic[1] else 0))
    xyz = s(u, v, grid=True)

    # Each point's v: its own where the rule gives one (parameters geometric), else its row's.
    v_of_point = fit.v_points if len(fit.v_points) else np.repeat(fit.v, fit.row_sizes)
    dev = np.abs(s(fit.u, v_of_point) - fit.points)
    t = np.array(r["tolerance"])
    used = (dev / np.where(t > 0, t, np.inf)).max(axis=1)
    row_of_point = np.repeat(np.arange(len(fit.row_sizes)), fit.row_sizes)

    fig = plt.figure(figsize=(12, 5))
    ax = fig.add_subplot(1, 2, 1, projection="3d")
    ax.plot_surface(xyz[..., 0], xyz[..., 1], xyz[..., 2], cmap="viridis", alpha=0.8,
                    linewidth=0, antialiased=True)
    ax.scatter(*fit.points.T, s=2, c="k")
    ax.set_title(f"{r['control_points'][0]} x {r['control_points'][1]} control points, "
                 f"{r['points']} points")
    ax.set_box_aspect(np.ptp(fit.points, axis=0) + 1e-12)
    ax2 = fig.add_subplot(1, 2, 2)
    sc = ax2.scatter(np.arange(len(used)), used, c=row_of_point, s=6, cmap="tab20")
    ax2.axhline(1.0, color="r", lw=1, label="tolerance T")
    ax2.set_xlabel("point (row after row)")
    ax2.set_ylabel("max per-axis deviation / T")
    ax2.set_ylim(0, 1.1)
    ax2.legend(loc="upper right")
    fig.colorbar(sc, ax=ax2, label="row")
    ax2.set_title(f"worst {used.max():.3f} T (row {r['worst']['row']}, point {r['worst']['index']})")
    fig.tight_layout()
    fig.savefig(a.out, dpi=80)
    print(f"plot_fit: wrote {a.out}; within tolerance: {'yes' if r['within_tolerance'] else 'NO'}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
