"""The cases of bench/adversarial.py: rows made from formulas and a seeded random generator
(each function takes a numpy Generator and returns a list of rows, each an array of points),
tweaks of a case's text (bad input), and the table of cases with their options and what is
expected of each ("fit": fitted; "input": refused as bad input)."""

import math

import numpy as np

# ----------------------------------------------------------------------------- data

def field(x, y):
    return (0.35 * np.exp(-((x - 0.3) ** 2 + (y + 0.2) ** 2) / 0.18)
            - 0.25 * np.exp(-((x + 0.4) ** 2 + (y - 0.35) ** 2) / 0.09)
            + 0.08 * np.sin(2.5 * x + 1.3 * y))


def grid(nx, ny, f=field, jitter=0.0, rng=None):
    rows = []
    xs = np.linspace(-1, 1, nx)
    for y in np.linspace(-1, 1, ny):
        x = xs + (rng.uniform(-jitter, jitter, nx) if jitter else 0)
        rows.append(np.column_stack([x, np.full(nx, y), f(x, np.full(nx, y))]))
    return rows


def reversed_rows(rng):
    """A smooth 60 x 50 grid, rows given last to first."""
    return grid(60, 50, rng=rng)[::-1]


def alternating_rows(rng):
    """A smooth 60 x 50 grid scanned back and forth (every other row reversed)."""
    return [r if k % 2 == 0 else r[::-1] for k, r in enumerate(grid(60, 50, rng=rng))]


def duplicated_points(rng):
    """A 50 x 40 grid where about a fifth of the points are repeated right after themselves."""
    out = []
    for r in grid(50, 40, rng=rng):
        rep = np.where(rng.uniform(size=len(r)) < 0.2, 2, 1)
        out.append(np.repeat(r, rep, axis=0))
    return out


def identical_rows(rng):
    """A 50 x 40 grid where row 20 is given twice in a row (the same points)."""
    g = grid(50, 40, rng=rng)
    return g[:21] + [g[20].copy()] + g[21:]


def two_point_row(rng):
    """A 50 x 40 grid where one row in the middle keeps only its two end points."""
    g = grid(50, 40, rng=rng)
    g[17] = g[17][[0, -1]]
    return g


def long_beside_short(rng):
    """30 rows of 5 points beside one row of 3000 points, all on one smooth surface."""
    rows = []
    for k, y in enumerate(np.linspace(-1, 1, 31)):
        n = 3000 if k == 15 else 5
        x = np.linspace(-1, 1, n)
        rows.append(np.column_stack([x, np.full(n, y), field(x, np.full(n, y))]))
    return rows


def spiked_contour(rng):
    """20 closed sections of a tube (80 points each); section 9 has a spike of 0.3 at one point."""
    rows = []
    for k, zc in enumerate(np.linspace(0, 2, 20)):
        a = np.linspace(0, 2 * math.pi, 80, endpoint=False)
        r = 1 + 0.1 * np.cos(2 * a) + 0.05 * zc
        if k == 9:
            r = r.copy()
            r[23] += 0.3
        rows.append(np.column_stack([r * np.cos(a), r * np.sin(a), np.full(80, zc)]))
    return rows


def zigzag_rows(rng):
    """40 rows, each a zigzag across a band of the surface: x runs on, y jumps back and forth."""
    rows = []
    for y0 in np.linspace(-0.95, 0.95, 40):
        x = np.linspace(-1, 1, 80)
        y = y0 + 0.02 * np.where(np.arange(80) % 2 == 0, 1.0, -1.0)
        rows.append(np.column_stack([x, y, field(x, y)]))
    return rows


def near_planar(rng):
    """A 40 x 40 grid of the plane z = 0.1 x + 0.2 y with noise of 1e-9."""
    return grid(40, 40, lambda x, y: 0.1 * x + 0.2 * y + rng.normal(0, 1e-9, x.shape), rng=rng)


def vertical_wall(rng):
    """A wall: 40 rows stacked in z, each a horizontal line along x with a small wave in y."""
    rows = []
    for z in np.linspace(0, 3, 40):
        x = np.linspace(-2, 2, 70)
        rows.append(np.column_stack([x, 0.1 * np.sin(2 * x + z), np.full(70, z)]))
    return rows


def dem_cliff(rng):
    """A 330 x 310 DEM (102,300 points) with a cliff: a step of 0.3 across a band 0.01 wide."""
    def f(x, y):
        return field(x, y) + 0.3 * 0.5 * (1 + np.tanh((x - 0.2 * y) / 0.005))
    return grid(330, 310, f, rng=rng)


def offset_1e7(rng):
    """A 80 x 60 terrain of 2 km x 2 km (heights in m), moved by 1e7 on x, y and z."""
    return [r * np.array([1000.0, 1000.0, 100.0]) + 1e7 for r in grid(80, 60, rng=rng)]


def smooth_small(rng):
    """A 30 x 25 smooth grid with a little jitter along x."""
    return grid(30, 25, jitter=0.01, rng=rng)


def tiny_rows(rng, count):
    """`count` rows of 2 or 3 points each across the smooth field."""
    rows = []
    for y in np.linspace(-1, 1, count):
        n = int(rng.integers(2, 4))
        x = np.sort(rng.uniform(-1, 1, n))
        rows.append(np.column_stack([x, np.full(n, y), field(x, np.full(n, y))]))
    return rows


def many_tiny_rows(rng):
    """20,000 rows of 2 or 3 points each across a smooth surface (50,000 points)."""
    return tiny_rows(rng, 20000)


def middle_pole(rng):
    """Closed sections of a vase pinched to one point (a pole) in the middle of the rows."""
    rows = []
    for zc in np.linspace(-1, 1, 21):
        if abs(zc) < 1e-12:
            rows.append(np.array([[0.0, 0.0, 0.0]]))
            continue
        a = np.linspace(0, 2 * math.pi, 60, endpoint=False)
        r = abs(zc) * (1 + 0.1 * np.cos(3 * a))
        rows.append(np.column_stack([r * np.cos(a), r * np.sin(a), np.full(60, zc)]))
    return rows


def two_point_rows(rng, height):
    """60 rows of 2 points each (fewer than degree + 1) near x = -1 and 1, z = height(x, y)."""
    rows = []
    for y in np.linspace(-1, 1, 60):
        x = np.array([-1.0, 1.0]) + rng.uniform(-0.05, 0.05, 2)
        rows.append(np.column_stack([x, np.full(2, y), height(x, np.full(2, y))]))
    return rows


def all_two_point_rows(rng):
    """60 rows of 2 points each across the smooth field: a ruled surface."""
    return two_point_rows(rng, field)


def two_point_rows_wave(rng):
    """60 rows of 2 points each across the sheet z = 0.3 sin(2x + y) + 0.2 cos(3y)."""
    return two_point_rows(rng, lambda x, y: 0.3 * np.sin(2 * x + y) + 0.2 * np.cos(3 * y))


def mixed_closed(rng):
    """30 closed sections of a tube, each starting at a random point, every third reversed."""
    rows = []
    for k, zc in enumerate(np.linspace(0, 3, 30)):
        n = int(rng.integers(50, 90))
        a = np.linspace(0, 2 * math.pi, n, endpoint=False) + rng.uniform(0, 2 * math.pi)
        r = 1 + 0.2 * np.cos(3 * a) + 0.1 * math.sin(zc)
        p = np.column_stack([r * np.cos(a), 0.7 * r * np.sin(a), np.full(n, zc)])
        rows.append(p[::-1] if k % 3 == 0 else p)
    return rows


def tiny_rows_1e5(rng):
    """50,000 rows of 2 or 3 points (about 10^5 points)."""
    return tiny_rows(rng, 50000)


def one_row(rng):
    return grid(40, 1, rng=rng)


def offset_1e8(rng):
    """The 80 x 60 terrain of 2 km moved by 1e8 on x, y and z."""
    return [r * np.array([1000.0, 1000.0, 100.0]) + 1e8 for r in grid(80, 60, rng=rng)]


def ragged_uneven(rng):
    """300 rows of 20 ... 400 points, each row crowded in its own place, each clipped to its
    own part of [-1, 1] (a random start and end)."""
    rows = []
    for y in np.linspace(-1, 1, 300):
        n = int(rng.integers(20, 401))
        a, b = np.sort(rng.uniform(-1, 1, 2))
        if b - a < 0.2:
            a, b = a - 0.1, b + 0.1
        t = np.sort(rng.uniform(0, 1, n)) ** rng.uniform(0.5, 2)
        x = a + (b - a) * t
        rows.append(np.column_stack([x, np.full(n, y), field(x, np.full(n, y))]))
    return rows


# ----------------------------------------------------------------------------- cases
# name: (make rows, CLI options, expected: "fit" or "input", text tweak of the file or None)

def empty(text):
    return ""


def comments_only(text):
    return "# nothing but a comment\n\n# and another\n"


def crlf(text):
    return text.replace("\n", "\r\n")


def blank_lines(text):
    return text.replace("\n\n", "\n\n   \n\t\n# between rows\n\n")


def put_nan(text):
    lines = text.split("\n")
    lines[57] = "0.5 nan 0.25"
    return "\n".join(lines)


def put_inf(text):
    lines = text.split("\n")
    lines[123] = "0.5 0.1 -inf"
    return "\n".join(lines)


def two_numbers(text):
    lines = text.split("\n")
    lines[40] = "0.5 0.25"
    return "\n".join(lines)


def huge_number(text):
    lines = text.split("\n")
    lines[12] = "1e400 0 0"
    return "\n".join(lines)


CASES = {
    "reversed_rows": (reversed_rows, [], "fit", None),
    "alternating_rows": (alternating_rows, [], "fit", None),
    "duplicated_points": (duplicated_points, [], "fit", None),
    "identical_rows": (identical_rows, [], "fit", None),
    "two_point_row": (two_point_row, [], "fit", None),
    "long_beside_short": (long_beside_short, [], "fit", None),
    "spiked_contour": (spiked_contour, ["--closed", "u"], "fit", None),
    "zigzag_rows": (zigzag_rows, [], "fit", None),
    "near_planar": (near_planar, [], "fit", None),
    "vertical_wall": (vertical_wall, [], "fit", None),
    "dem_cliff_1e5": (dem_cliff, [], "fit", None),
    "offset_1e7": (offset_1e7, [], "fit", None),
    "offset_1e7_tol1e-7": (offset_1e7, ["--tol-rel", "1e-7"], "fit", None),
    "tol_1e-7": (smooth_small, ["--tol-rel", "1e-7"], "fit", None),
    "tol_1e-9": (smooth_small, ["--tol-rel", "1e-9"], "fit", None),
    "tol_axis_zero": (smooth_small, ["--tol", "0.002,0.002,0"], "fit", None),
    "middle_pole": (middle_pole, ["--closed", "u"], "fit", None),
    "many_tiny_rows": (many_tiny_rows, [], "fit", None),
    "all_two_point_rows": (all_two_point_rows, [], "fit", None),
    "two_point_rows_wave": (two_point_rows_wave, [], "fit", None),
    "mixed_closed": (mixed_closed, ["--closed", "u"], "fit", None),
    "tiny_rows_1e5": (tiny_rows_1e5, [], "fit", None),
    "offset_1e8_tol1e-9": (offset_1e8, ["--tol-rel", "1e-9"], "fit", None),
    "ragged_uneven": (ragged_uneven, [], "fit", None),
    "ragged_uneven_1e-2": (ragged_uneven, ["--tol-rel", "1e-2"], "fit", None),
    "dem_cliff_1e5_1e-9": (dem_cliff, ["--tol-rel", "1e-9"], "fit", None),
    "crlf": (smooth_small, [], "fit", crlf),
    "blank_lines": (smooth_small, [], "fit", blank_lines),
    "nan_value": (smooth_small, [], "input", put_nan),
    "inf_value": (smooth_small, [], "input", put_inf),
    "two_numbers": (smooth_small, [], "input", two_numbers),
    "beyond_double": (smooth_small, [], "input", huge_number),
    "one_row": (one_row, [], "input", None),
    "empty_file": (smooth_small, [], "input", empty),
    "comments_only": (smooth_small, [], "input", comments_only),
}

CHEAP_POINTS = 20000  # below this many points, also write STL, OBJ (and STEP where built)


def rows_text(rows):
    out = ["# generated by bench/adversarial.py"]
    for r in rows:
        out.extend(f"{p[0]:.17g} {p[1]:.17g} {p[2]:.17g}" for p in r)
        out.append("")
    return "\n".join(out) + "\n"
