"""sfit.FrozenRefit: least squares at a fit's frozen counts, knots and parameters."""

import numpy as np
import pytest

import sfit


def terrain(m=20, ragged=False):
    rows = []
    for j in range(m):
        n = 25 + (j % 4) * 3 if ragged else 30
        f = np.linspace(0, 1, n)
        s = f * (0.6 + 0.4 * f) if ragged else f
        t = j / (m - 1)
        z = 10 * np.sin(3 * s) * np.cos(2 * t) + 5 * s * t * t + 0.5 * np.sin(17 * s + 11 * t)
        rows.append(np.column_stack([100 * s, np.full(n, 100 * t), z]))
    return rows


@pytest.mark.parametrize("ragged", [False, True])
def test_refit_and_influence(ragged):
    rows = terrain(ragged=ragged)
    fit = sfit.fit(rows, tol_rel=1e-3, parameters="uniform")
    frozen = sfit.FrozenRefit(fit)
    assert frozen.seconds >= 0
    same = frozen.refit(rows)
    # The fit's own least-squares surface, but for the refit's small smoothing term.
    size = np.abs(fit.surface.control_points).max()
    diff = np.abs(same.surface.control_points - fit.surface.control_points).max()
    assert diff < 1e-6 * size
    assert same.report["within_tolerance"]
    assert np.array_equal(same.u, fit.u)

    # A move: the refit changes by the influence times the move (linear), to round-off.
    d = np.array([0.5, -0.25, 2.0])
    moved = [r.copy() for r in rows]
    moved[4][7] += d
    after = frozen.refit(moved)
    g = frozen.influence(4, 7)
    cu, cv = fit.surface.count
    assert g.shape == (cu * cv,)
    full = fit.surface.control_points.shape
    delta = (after.surface.control_points - same.surface.control_points)[: full[0], : full[1]]
    predicted = g.reshape(cu, cv)[..., None] * d
    assert np.abs(delta[:cu, :cv] - predicted).max() < 1e-12 * size
    assert np.abs(delta).max() > 1e-3
    # A move far beyond T: the report says so, as the library's check does.
    far = [r.copy() for r in rows]
    far[4][7] += [0, 0, 50.0]
    assert not frozen.refit(far).report["within_tolerance"]


def test_refusals():
    rows = terrain()
    fit = sfit.fit(rows, tol_rel=1e-3)
    frozen = sfit.FrozenRefit(fit)
    with pytest.raises(sfit.Error) as e:
        frozen.refit(terrain(ragged=True))
    assert e.value.code == "usage"
    with pytest.raises(sfit.Error):
        frozen.influence(20, 0)
    weighted = [np.column_stack([r, np.full(len(r), 2.0)]) for r in rows]
    with pytest.raises(sfit.Error, match="weighted"):
        sfit.FrozenRefit(sfit.fit(weighted, tol_rel=1e-3))
