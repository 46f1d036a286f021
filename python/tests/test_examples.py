"""The Python examples run: Dask tiles on a small grid, and the matplotlib plot."""

import json
import os
import subprocess
import sys

import numpy as np

import sfit
from conftest import REPO, example

EXAMPLES = REPO / "examples" / "python"


def run(script, *args, timeout=300):
    r = subprocess.run([sys.executable, str(EXAMPLES / script), *map(str, args)],
                       capture_output=True, text=True, timeout=timeout, env=os.environ.copy())
    assert r.returncode == 0, r.stdout + r.stderr
    return r.stdout


def test_dask_tiles_on_a_small_grid(tmp_path):
    out = tmp_path / "tiles"
    line = run("dask_tiles.py", "-o", out, "--size", "90", "130", "--tile", "40", "--overlap",
               "4", "--workers", "2")
    assert "within tolerance: yes" in line
    summary = json.loads((out / "summary.json").read_text())
    assert len(summary["tiles"]) == 3 * 4 and summary["all_within_tolerance"]
    # Each tile on the cluster equals a fit of the same tile here, bit for bit.
    sys.path.insert(0, str(EXAMPLES))
    import dask_tiles

    z = dask_tiles.terrain(90, 130)
    ranges_r = dask_tiles.tile_ranges(90, 40, 4)
    ranges_c = dask_tiles.tile_ranges(130, 40, 4)
    fitted = {}
    for t in summary["tiles"]:
        (r0, r1), (c0, c1) = ranges_r[t["tile"][0]], ranges_c[t["tile"][1]]
        assert t["x"] == [c0, c1 - 1] and t["y"] == [r0, r1 - 1]
        assert t["points"] == (r1 - r0) * (c1 - c0)
        saved = json.loads((out / t["file"]).read_text())
        assert saved["report"]["within_tolerance"]
        assert max(saved["report"]["max_deviation"]) <= summary["tolerance"]
        y, x = np.mgrid[r0:r1, c0:c1].astype(float)
        here = sfit.fit(np.stack([x, y, z[r0:r1, c0:c1]], axis=-1), tol=summary["tolerance"])
        assert np.array_equal(sfit.load_surface(str(out / t["file"])).control_points,
                              here.surface.control_points)
        fitted[tuple(t["tile"])] = here.surface(here.u, np.repeat(here.v, here.row_sizes)) \
            .reshape(r1 - r0, c1 - c0, 3)
    # The seams: the largest difference of two neighbours at the points they share, within
    # 2T, as measured here from the local fits.
    seam = np.zeros(3)
    for (i, j), a in fitted.items():
        if (i, j + 1) in fitted:
            w = ranges_c[j][1] - ranges_c[j + 1][0]
            seam = np.maximum(seam, np.abs(a[:, -w:] - fitted[(i, j + 1)][:, :w]).max((0, 1)))
        if (i + 1, j) in fitted:
            w = ranges_r[i][1] - ranges_r[i + 1][0]
            seam = np.maximum(seam, np.abs(a[-w:] - fitted[(i + 1, j)][:w]).max((0, 1)))
    assert summary["seam"] == seam.tolist() and 0 < max(summary["seam"]) <= 2 * summary["tolerance"]


def test_plot_fit_writes_a_png(tmp_path):
    png = tmp_path / "wing.png"
    line = run("plot_fit.py", example("d150_wing"), "--closed", "u", "-o", png, "--samples", "30")
    assert "within tolerance: yes" in line
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and png.stat().st_size > 10000
