"""Every error path raises sfit.Error (a ValueError) with the CLI's code and one-line message."""

import os

import numpy as np
import pytest

import sfit
from conftest import BAD_INPUT, example, run_cli, wavy_grid


def raises(code, f, *args, **kwargs):
    with pytest.raises(sfit.Error) as info:
        f(*args, **kwargs)
    e = info.value
    assert isinstance(e, ValueError)
    assert e.code == code, str(e)
    assert "\n" not in str(e)
    return e


EXIT = {"usage": 2, "input-unreadable": 3, "input-syntax": 4, "input-data": 5, "output-write": 6,
        "tolerance-not-met": 7}


@pytest.mark.parametrize(
    "kwargs,option",
    [
        ({"closed": "w"}, "closed"),
        ({"closed": 1}, "closed"),
        ({"search": "slow"}, "search"),
        ({"parameters": "arc"}, "parameters"),
        ({"tol": 0.1, "tol_rel": 0.01}, "tol_rel"),
        ({"tol_rel": 2.0}, "tol_rel"),
        ({"tol": (1, 2)}, "tol"),
        ({"tol": "0.1"}, "tol"),
        ({"tol": -1}, "tol"),  # the keyword given, checked by the option table
        ({"tol": float("nan")}, "tol"),
        ({"degree": 0}, "degree"),
        ({"degree_v": 21}, "degree_v"),
        ({"degree": 2.5}, "degree"),
        ({"threads": -1}, "threads"),
        ({"row_count_hints": "abc"}, "row_count_hints"),
    ],
)
def test_bad_options_are_usage_errors(ship_rows, kwargs, option):
    e = raises("usage", sfit.fit, ship_rows, **kwargs)
    assert e.option == option and e.exit_code == 2
    assert str(e).startswith(option + ": ")


def test_an_unknown_keyword_is_a_type_error_as_in_any_python_function(ship_rows):
    # fit()'s signature lists every option (inspect.signature); Python refuses the others.
    with pytest.raises(TypeError, match="bogus"):
        sfit.fit(ship_rows, bogus=1)


def test_non_finite_coordinate_names_row_and_index(ship_rows):
    rows = [r.copy() for r in ship_rows]
    rows[4][3, 2] = np.nan
    e = raises("input-data", sfit.fit, rows)
    assert (e.row, e.index, e.exit_code) == (4, 3, 5)
    assert str(e) == "row 4, point 3: coordinate is not a finite number"
    rows[4][3, 2] = np.inf
    assert raises("input-data", sfit.fit, rows).row == 4
    grid = wavy_grid()
    grid[7, 11, 0] = -np.inf
    e = raises("input-data", sfit.fit, grid)
    assert (e.row, e.index) == (7, 11)


@pytest.mark.parametrize(
    "rows,row",
    [
        (np.zeros((5, 3)), None),  # one row as a 2-D array
        (np.zeros((4, 5, 2)), None),  # not 3 coordinates
        (np.zeros((2, 3, 3, 1)), None),
        ([np.zeros((4, 3)), np.zeros((4, 2))], 1),
        ([np.zeros((4, 3)), np.zeros(12)], 1),
        ([np.zeros((4, 3)), np.zeros((4, 3), dtype=complex)], 1),
        ([np.zeros((4, 3)), np.array([["a", "b", "c"]])], 1),
        ([np.zeros((4, 3)), np.ones((4, 3), dtype=bool)], 1),
        ([np.zeros((4, 3)), [[1, 2, 3], [4, 5]]], 1),  # ragged
        (np.zeros((3, 4, 3), dtype=object), None),
        ("rows.rows", None),
        (42, None),
    ],
)
def test_wrong_shapes_and_dtypes_are_rejected(rows, row):
    e = raises("input-data", sfit.fit, rows)
    assert e.row == row


def test_too_few_rows_and_empty_rows(ship_rows):
    assert "at least 2 rows" in str(raises("input-data", sfit.fit, ship_rows[:1]))
    assert raises("input-data", sfit.fit, []).code == "input-data"
    e = raises("input-data", sfit.fit, [ship_rows[0], np.zeros((0, 3)), ship_rows[2]])
    assert e.row == 1
    assert raises("input-data", sfit.fit, ship_rows[:2], closed="v").code == "input-data"
    e = raises("input-data", sfit.fit, [ship_rows[0], ship_rows[1][:2], ship_rows[2]], closed="u")
    assert e.row == 1


def test_flat_data_is_rejected():
    line = np.stack([np.linspace(0, 1, 5)] * 3, axis=-1)
    assert "straight line" in str(raises("input-data", sfit.fit, [line, line]))


def test_tolerance_not_met_as_the_cli(cli, tmp_path):
    path = str(BAD_INPUT / "degree20_interpolation_not_met.rows")
    e = raises("tolerance-not-met", sfit.fit, sfit.load_rows(path), degree=20, tol=0)
    assert e.exit_code == 7
    code, err = run_cli(cli, "fit", path, "--degree", "20", "--tol", "0", "-o", tmp_path / "x.json")
    assert code == 7
    # The CLI adds the file name in front of the same message.
    assert err.strip().splitlines()[-1] == f"sfit: error: {path}: {e}"


@pytest.mark.parametrize(
    "name,code",
    [("two_numbers.rows", "input-syntax"), ("nan.rows", "input-data"), ("empty.rows", "input-data"),
     ("non_numeric.rows", "input-syntax")],
)
def test_reader_errors_are_the_clis_lines(cli, tmp_path, name, code):
    path = str(BAD_INPUT / name)
    e = raises(code, sfit.load_rows, path)
    assert e.file == path and e.exit_code == EXIT[code]
    rc, err = run_cli(cli, "fit", path, "-o", tmp_path / "x.json")
    assert rc == EXIT[code]
    assert err.strip().splitlines()[-1] == f"sfit: error: {e}"


def test_reader_error_places():
    e = raises("input-syntax", sfit.load_rows, str(BAD_INPUT / "two_numbers.rows"))
    assert (e.line, e.column, e.row, e.index) == (3, 4, 0, 2)


def test_unreadable_files(tmp_path):
    e = raises("input-unreadable", sfit.load_rows, str(tmp_path / "missing.rows"))
    assert e.exit_code == 3 and e.file.endswith("missing.rows")
    raises("input-unreadable", sfit.load_surface, str(tmp_path / "missing.json"))
    raises("input-unreadable", sfit.load_rows, str(tmp_path))


def test_bad_surface_files():
    raises("input-syntax", sfit.load_surface, str(BAD_INPUT / "plain_text.json"))
    raises("input-data", sfit.load_surface, str(BAD_INPUT / "not_a_surface.json"))


def test_output_errors(tmp_path, ship_rows):
    s = sfit.fit(ship_rows).surface
    e = raises("output-write", s.save, str(tmp_path / "no" / "such" / "folder.json"))
    assert e.exit_code == 6
    e = raises("usage", s.save, str(tmp_path / "surface.xyz"))
    assert e.option == "-o"
    assert not os.path.exists(tmp_path / "surface.xyz")


def test_evaluation_errors(ship_rows):
    s = sfit.fit(ship_rows).surface
    raises("input-data", s, [0.1, np.nan], [0.2, 0.3])
    raises("input-data", s, 0.1, np.inf)
    raises("input-data", s, np.zeros((2, 2)), np.zeros((2, 2)))
    raises("input-data", s, ["a"], [1.0])
    raises("usage", s, [0.1, 0.2], [0.1, 0.2, 0.3])
    raises("usage", s.derivative, 0.1, 0.2, 3, 0)
    raises("usage", s.derivative, 0.1, 0.2, -1, 0)
    raises("usage", s.derivative, 0.1, 0.2, 1, 2)


def test_fortran_order_and_strided_arrays_are_converted():
    grid = wavy_grid()
    reference = sfit.fit(grid, tol=0.01).surface.control_points
    fortran = np.asfortranarray(grid)
    assert not fortran.flags.c_contiguous
    assert np.array_equal(sfit.fit(fortran, tol=0.01).surface.control_points, reference)
    wide = np.zeros((30, 80, 3))
    wide[:, ::2] = grid
    strided = wide[:, ::2]
    assert not strided.flags.c_contiguous
    assert np.array_equal(sfit.fit(strided, tol=0.01).surface.control_points, reference)
    rows_f = [np.asfortranarray(r) for r in grid]
    assert np.array_equal(sfit.fit(rows_f, tol=0.01).surface.control_points, reference)
    as_float32 = grid.astype(np.float32)
    a = sfit.fit(as_float32, tol=0.01)
    b = sfit.fit(as_float32.astype(np.float64), tol=0.01)
    assert np.array_equal(a.surface.control_points, b.surface.control_points)
    ints = np.rint(grid * 100 + 1000).astype(np.int32)
    reference_ints = sfit.fit(ints.astype(np.float64), tol=1).surface.control_points
    for dtype in (np.int32, np.int64, np.uint16, np.uint64, np.float16, np.longdouble):
        converted = sfit.fit(ints.astype(dtype), tol=1)
        assert np.array_equal(converted.surface.control_points, reference_ints), dtype
    as_lists = grid.tolist()
    assert np.array_equal(sfit.fit(as_lists, tol=0.01).surface.control_points, reference)
