"""sfit.fit_curve(): one row within the tolerance, open and closed."""

import numpy as np
import pytest

import sfit
from conftest import example


def deviation(cf, points):
    return np.abs(cf.curve(cf.parameters) - points)


@pytest.mark.parametrize("name,closed", [("ship_px121_stations", False), ("d150_wing", True)])
def test_curve_within_tolerance(name, closed):
    row = max(sfit.load_rows(example(name)), key=len)
    tol = 1e-3 * np.linalg.norm(row.max(0) - row.min(0))
    cf = sfit.fit_curve(row, tol=tol, closed=closed)
    assert cf.curve.periodic == closed
    assert (deviation(cf, row) <= tol).all()
    assert np.allclose(deviation(cf, row).max(0), cf.max_deviation)
    n = cf.curve.count
    assert cf.curve.control_points.shape == (n + 3 if closed else n, 3)
    assert len(cf.curve.knots) == len(cf.curve.control_points) + 4
    # The default tolerance is the CLI's fraction of the row's diagonal.
    assert sfit.fit_curve(row, closed=closed).curve.count == n


def test_fewer_points_than_the_tolerance_needs_interpolate():
    row = np.array([[0.0, 0, 0], [1, 2, 0], [2, 0, 1], [3, 1, 1], [4, 0, 0]])
    cf = sfit.fit_curve(row, tol=0, degree=3)
    assert cf.curve.count == 5
    assert deviation(cf, row).max() < 1e-12


def test_curve_parameters_and_derivative():
    t = np.linspace(0, 1, 40)
    row = np.stack([t, t**2, np.sin(3 * t)], axis=-1)
    cf = sfit.fit_curve(row, tol=1e-4, parameters="chord", search="linear")
    assert cf.scaled
    c = cf.curve
    h = 1e-6
    assert np.allclose(c.derivative(0.5), (c(0.5 + h) - c(0.5 - h)) / (2 * h), rtol=1e-5)
    assert c([0.1, 0.2]).shape == (2, 3) and c(0.1).shape == (3,)


@pytest.mark.parametrize(
    "kwargs,code",
    [
        ({"degree": 0}, "usage"),
        ({"degree": 21}, "usage"),
        ({"tol": -1.0}, "usage"),
        ({"search": "x"}, "usage"),
        ({"parameters": "fewest"}, "usage"),
    ],
)
def test_curve_option_errors(kwargs, code):
    row = np.random.default_rng(1).random((10, 3))
    with pytest.raises(sfit.Error) as e:
        sfit.fit_curve(row, **kwargs)
    assert e.value.code == code


def test_curve_data_errors():
    for points, closed in [(np.zeros((0, 3)), False), (np.zeros((2, 3)), True), (np.zeros((4, 2)), False)]:
        with pytest.raises(sfit.Error) as e:
            sfit.fit_curve(points, tol=0.1, closed=closed)
        assert e.value.code == "input-data"
    bad = np.random.default_rng(2).random((8, 3))
    bad[5, 1] = np.nan
    with pytest.raises(sfit.Error) as e:
        sfit.fit_curve(bad, tol=0.1)
    assert e.value.index == 5
