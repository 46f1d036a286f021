"""Type stub of the sfit package (the compiled part is sfit._sfit; see docs/python.md)."""

from typing import Any, Callable, Sequence, Union

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

class Surface:
    """Tensor-product B-spline surface on uniform knots; u along the rows, v across."""

    degree: tuple[int, int]
    degree_u: int
    degree_v: int
    periodic: tuple[bool, bool]
    count: tuple[int, int]
    knots_u: npt.NDArray[np.float64]
    knots_v: npt.NDArray[np.float64]
    control_points: npt.NDArray[np.float64]  # (nu_full, nv_full, 3), stored form
    u_end: float
    v_end: float
    def __call__(self, u: ArrayLike, v: ArrayLike, grid: bool = False, threads: int = 0) -> npt.NDArray[np.float64]: ...
    def derivative(self, u: ArrayLike, v: ArrayLike, du: int = 1, dv: int = 0, grid: bool = False, threads: int = 0) -> npt.NDArray[np.float64]: ...
    def normal(self, u: ArrayLike, v: ArrayLike, grid: bool = False, threads: int = 0) -> npt.NDArray[np.float64]: ...
    def save(self, path: str, mesh: bool = False, mesh_density: int = 0, fields: bool = False, units: str = "mm") -> None: ...
    def to_json(self) -> dict[str, Any]: ...

class Fit:
    """A fitted surface and what it achieved."""

    surface: Surface
    report: dict[str, Any]  # the keys of the JSON report
    u: npt.NDArray[np.float64]  # (P,): u of every point, row after row
    v: npt.NDArray[np.float64]  # (M,): v of every row
    points: npt.NDArray[np.float64]  # (P, 3)
    row_sizes: list[int]
    def save(self, path: str, mesh: bool = False, mesh_density: int = 0, fields: bool = False, units: str = "mm") -> None: ...

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
    tol_rel: float | None = None,
    degree: int = 3,
    degree_u: int | None = None,
    degree_v: int | None = None,
    closed: str = "",
    threads: int = 0,
    *,
    search: str = "fast",
    parameters: str = "paper",
    row_count_hints: Sequence[int] | None = None,
    column_count_hints: Sequence[int] | None = None,
    progress: Callable[[FitProgress], bool | None] | None = None,
    **options: Any,
) -> Fit:
    """Fits rows of points ((N_j, 3) arrays, or an (M, N, 3) array) within tolerance T."""

class IncrementalFit:
    """A fit that follows edits of its rows; each edit equals sfit.fit() of the edited rows."""

    fit: Fit
    rows: list[npt.NDArray[np.float64]]
    rows_refitted: int
    def __init__(self, rows: Rows, **options: Any) -> None: ...
    def move_point(self, row: int, index: int, to: ArrayLike) -> Fit: ...
    def insert_point(self, row: int, index: int, point: ArrayLike) -> Fit: ...
    def erase_point(self, row: int, index: int) -> Fit: ...
    def replace_row(self, row: int, points: ArrayLike) -> Fit: ...

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
def load_rows(path: str) -> list[npt.NDArray[np.float64]]: ...
def load_surface(path: str) -> Surface: ...
def output_formats() -> list[str]: ...
