"""sfit: rows of 3D points to one B-spline surface within a per-axis tolerance.

The surface has as few control points as possible on uniform knots (Vergeest 1989, SFIT01),
and every data point is checked on it. u runs along a row, v across the rows.

    import numpy as np, sfit
    rows = sfit.load_rows("examples/ship_px121_stations.rows")
    fit = sfit.fit(rows, tol_rel=1e-3)
    fit.report["max_deviation"], fit.surface.count
    xyz = fit.surface(np.linspace(0, fit.surface.u_end, 50), [0.0], grid=True)

See docs/python.md.
"""

from . import _sfit
from ._errors import Error
from ._signatures import Curvature, curvature as _curvature, install as _install

_sfit.Surface.curvature = _curvature
_install(
    _sfit,
    classes=[
        _sfit.Surface,
        _sfit.Fit,
        _sfit.IncrementalFit,
        _sfit.FrozenRefit,
        _sfit.Curve,
        _sfit.CurveFit,
    ],
    functions=["fit", "fit_curve", "fit_options", "load_rows", "load_surface", "output_formats"],
    fit_like={"fit", "IncrementalFit.__init__"},
)

from ._sfit import (  # noqa: E402  (after the signatures are in place)
    Curve,
    CurveFit,
    Fit,
    FitProgress,
    FrozenRefit,
    IncrementalFit,
    Surface,
    __version__,
    fit,
    fit_curve,
    fit_options,
    load_rows,
    load_surface,
    output_formats,
)

__all__ = [
    "Curvature",
    "Curve",
    "CurveFit",
    "Error",
    "Fit",
    "FitProgress",
    "FrozenRefit",
    "IncrementalFit",
    "Surface",
    "__version__",
    "fit",
    "fit_curve",
    "fit_options",
    "load_rows",
    "load_surface",
    "output_formats",
]
