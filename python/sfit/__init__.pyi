"""Type stub of the sfit package (the compiled part is sfit._sfit; see docs/python.md)."""

from typing import Any, Callable, NamedTuple, Sequence, Union

import numpy as np
import numpy.typing as npt

ArrayLike = npt.ArrayLike
Rows = Union[Sequence[npt.ArrayLike], npt.NDArray[Any]]
PerAxis = Union[float, Sequence[float]]

__version__: str

class Error(ValueError):
    """Bad input or a failed fit; str() is the CLI's one-line message."""

    code: str  # "usage", "input-unreadable", "input-syntax", "input-data", "output-write",
    #            "tolerance-not-met", "internal"
    exit_code: int  # the CLI's exit code, 2 ... 8
    message: str
    file: str | None
    line: int | None
    column: int | None
    row: int | None
    index: int | None
    option: str | None
    values: tuple[float, ...]
    fit: "Fit | None"

class Curvature(NamedTuple):
    """Curvature with respect to the unit normal S_u x S_v (k1 >= k2)."""

    gaussian: Any
    mean: Any
    k1: Any
    k2: Any

class Surface:
    """Tensor-product B-spline surface on uniform knots; u along the rows, v across."""

    degree: tuple[int, int]
    degree_u: int
    degree_v: int
    periodic: tuple[bool, bool]
    count: tuple[int, int]
    knots_u: npt.NDArray[np.float64]
    knots_v: npt.NDArray[np.float64]
    uniform_knots: tuple[bool, bool]
    control_points: npt.NDArray[np.float64]  # (nu_full, nv_full, 3), stored form
    u_end: float
    v_end: float
    def __call__(self, u: ArrayLike, v: ArrayLike, grid: bool = False, threads: int = 0) -> npt.NDArray[np.float64]:
        """S(u, v): (n, 3) pointwise; grid=True: (len(u), len(v), 3), [i, j] = S(u[i], v[j])."""
    def derivative(self, u: ArrayLike, v: ArrayLike, du: int = 1, dv: int = 0, grid: bool = False, threads: int = 0) -> npt.NDArray[np.float64]: ...
    def derivatives(self, u: ArrayLike, v: ArrayLike, order: int = 1, grid: bool = False, threads: int = 0) -> npt.NDArray[np.float64]:
        """S, S_u, S_v (, S_uu, S_uv, S_vv) in the axis before the last, from one basis pass."""
    def normal(self, u: ArrayLike, v: ArrayLike, grid: bool = False, threads: int = 0) -> npt.NDArray[np.float64]: ...
    def curvature(self, u: ArrayLike, v: ArrayLike, grid: bool = False, threads: int = 0) -> Curvature: ...
    def closest_point(self, points: ArrayLike, threads: int = 0) -> tuple[Any, Any]:
        """(u, v) of the nearest point of the surface: numbers for one point, (n,) arrays for (n, 3)."""
    @staticmethod
    def from_knots(knots_u: ArrayLike, knots_v: ArrayLike, control_points: ArrayLike, degree_u: int, degree_v: int, periodic_u: bool = False, periodic_v: bool = False) -> Surface: ...
    def save(self, path: str, mesh: bool = False, mesh_density: int = 0, fields: bool = False, units: str = "mm", obj_freeform: bool = False, normals: str = "auto") -> None: ...
    def to_json(self) -> dict[str, Any]: ...

class Fit:
    """A fitted surface and what it achieved."""

    surface: Surface
    report: dict[str, Any]  # the keys of the JSON report
    u: npt.NDArray[np.float64]  # (P,): u of every point, row after row
    v: npt.NDArray[np.float64]  # (M,): v of every row
    v_points: npt.NDArray[np.float64]  # (P,) or empty: v of every point (parameters 'geometric')
    points: npt.NDArray[np.float64]  # (P, 3)
    row_sizes: list[int]
    def save(self, path: str, mesh: bool = False, mesh_density: int = 0, fields: bool = False, units: str = "mm", obj_freeform: bool = False, normals: str = "auto") -> None: ...

class FitProgress:
    """What a fit is doing, passed to the `progress` callable of sfit.fit()."""

    phase: str  # "search", "lower bound", "rows", "columns", "check", "fold guard"
    done: int
    total: int
    pairs_tried: int
    best: tuple[int, int] | None  # the fewest (nu, nv) found to hold so far
    seconds: float

def fit(
    rows: Rows,
    tol: PerAxis | None = None,
    *,
    degree: int = 3,
    degree_u: int | None = None,
    degree_v: int | None = None,
    tol_rel: float = 0.001,
    closed: str = "none",
    search: str = "fast",
    parameters: str = "auto",
    knots: str = "corners",
    method: str = "surface",
    norm: str = "auto",
    seam: str = "align",
    orient: str = "auto",
    fold_guard: bool = True,
    rerepresent: str = "paper",
    threads: int = 0,
    row_count_hints: Sequence[int] | None = None,
    column_count_hints: Sequence[int] | None = None,
    progress: Callable[[FitProgress], bool | None] | None = None,
) -> Fit:
    """Fits rows of points ((N_j, 3) arrays, or an (M, N, 3) array; a 4th column: weights)
    within tolerance T. Every option's default is the library's (sfit.fit_options(), docs/options.md)."""

class IncrementalFit:
    """A fit that follows edits of its rows; each edit equals sfit.fit() of the edited rows."""

    fit: Fit
    rows: list[npt.NDArray[np.float64]]
    rows_refitted: int
    def __init__(
        self,
        rows: Rows,
        *,
        degree: int = 3,
        degree_u: int | None = None,
        degree_v: int | None = None,
        tol: PerAxis | None = None,
        tol_rel: float = 0.001,
        closed: str = "none",
        search: str = "fast",
        parameters: str = "auto",
        knots: str = "corners",
        method: str = "surface",
        norm: str = "auto",
        seam: str = "align",
        orient: str = "auto",
        fold_guard: bool = True,
        rerepresent: str = "paper",
        threads: int = 0,
        row_count_hints: Sequence[int] | None = None,
        column_count_hints: Sequence[int] | None = None,
        progress: Callable[[str, int, int], None] | None = None,
    ) -> None: ...
    def move_point(self, row: int, index: int, to: ArrayLike) -> Fit: ...
    def insert_point(self, row: int, index: int, point: ArrayLike) -> Fit: ...
    def erase_point(self, row: int, index: int) -> Fit: ...
    def replace_row(self, row: int, points: ArrayLike) -> Fit: ...

class FrozenRefit:
    """Least squares at a finished fit's counts, knots and parameters, frozen."""

    seconds: float
    def __init__(self, fit: Fit) -> None: ...
    def refit(self, rows: Rows) -> Fit: ...
    def influence(self, row: int, index: int) -> npt.NDArray[np.float64]: ...

class Curve:
    degree: int
    periodic: bool
    count: int
    t_end: float
    knots: npt.NDArray[np.float64]
    control_points: npt.NDArray[np.float64]
    def __call__(self, t: ArrayLike) -> npt.NDArray[np.float64]: ...
    def derivative(self, t: ArrayLike, order: int = 1) -> npt.NDArray[np.float64]: ...

class CurveFit:
    curve: Curve
    parameters: npt.NDArray[np.float64]
    max_deviation: npt.NDArray[np.float64]
    solves: int
    scaled: bool

def fit_curve(
    points: ArrayLike,
    tol: PerAxis | None = None,
    degree: int = 3,
    closed: bool = False,
    search: str = "fast",
    parameters: str = "paper",
    hint: int = 0,
) -> CurveFit: ...
def load_rows(path: str) -> list[npt.NDArray[np.float64]]:
    """(N_j, 3) arrays, or (N_j, 4) (x, y, z, w) when the file carries weights."""
def load_surface(path: str) -> Surface: ...
def output_formats() -> list[str]: ...
def fit_options() -> list[dict[str, Any]]: ...
