"""sfit.IncrementalFit: each edit equals a full fit of the edited rows, bit for bit."""

import numpy as np
import pytest

import sfit
from conftest import example


def full_fit(rows, tol, closed=""):
    return sfit.fit(rows, tol=tol, closed=closed)


def assert_same(a, b):
    assert np.array_equal(a.surface.control_points, b.surface.control_points)
    assert np.array_equal(a.u, b.u) and np.array_equal(a.v, b.v)
    assert a.report["row_counts"] == b.report["row_counts"]


@pytest.mark.parametrize("name,closed", [("ship_px121_stations", ""), ("d150_wing", "u")])
def test_edits_equal_full_fits(name, closed):
    rows = sfit.load_rows(example(name))
    tol = 0.05 if closed else 0.08
    inc = sfit.IncrementalFit(rows, tol=tol, closed=closed)
    assert_same(inc.fit, full_fit(rows, tol, closed))
    rows = [r.copy() for r in rows]

    moved = rows[2][3] + [0.01, -0.02, 0.005]
    f = inc.move_point(2, 3, moved)
    rows[2][3] = moved
    assert_same(f, full_fit(rows, tol, closed))

    new = (rows[1][0] + rows[1][1]) / 2
    f = inc.insert_point(1, 1, new)
    rows[1] = np.insert(rows[1], 1, new, axis=0)
    assert_same(f, full_fit(rows, tol, closed))

    f = inc.erase_point(1, 1)
    rows[1] = np.delete(rows[1], 1, axis=0)
    assert_same(f, full_fit(rows, tol, closed))

    replacement = rows[3][::-1][::-1] * 1.0  # same points, a fresh array
    replacement[0] += 0.001
    f = inc.replace_row(3, replacement)
    rows[3] = replacement
    assert_same(f, full_fit(rows, tol, closed))
    assert all(np.array_equal(a, b) for a, b in zip(inc.rows, rows))
    assert inc.rows_refitted >= 1


def test_bad_edits_raise_and_leave_the_state():
    rows = sfit.load_rows(example("ship_px121_stations"))
    inc = sfit.IncrementalFit(rows)
    before = inc.fit.surface.control_points
    for call, code in [
        (lambda: inc.move_point(99, 0, [0, 0, 0]), "usage"),
        (lambda: inc.move_point(0, 99, [0, 0, 0]), "usage"),
        (lambda: inc.move_point(-1, 0, [0, 0, 0]), "usage"),
        (lambda: inc.move_point(0, 0, [np.nan, 0, 0]), "input-data"),
        (lambda: inc.move_point(0, 0, [1, 2]), "input-data"),
        (lambda: inc.insert_point(0, 99, [0, 0, 0]), "usage"),
        (lambda: inc.erase_point(0, 99), "usage"),
        (lambda: inc.replace_row(0, np.zeros((0, 3))), "usage"),
        (lambda: inc.replace_row(0, np.zeros((4, 2))), "input-data"),
    ]:
        with pytest.raises(sfit.Error) as e:
            call()
        assert e.value.code == code
    assert np.array_equal(inc.fit.surface.control_points, before)


def test_bad_options_of_incremental_fit():
    with pytest.raises(sfit.Error) as e:
        sfit.IncrementalFit(sfit.load_rows(example("ship_px121_stations")), closed="x")
    assert e.value.code == "usage" and e.value.option == "closed"
