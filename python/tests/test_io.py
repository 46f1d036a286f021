"""sfit.load_rows(): every input format `sfit fit` reads, through the CLI's own readers."""

import numpy as np

import sfit
from conftest import assert_same_surface, cli_fit, example, run_cli


def test_rows_file_gives_one_array_per_row():
    rows = sfit.load_rows(example("iea3p4mw_blade_ragged9"))
    assert len(rows) == 9
    assert all(r.dtype == np.float64 and r.ndim == 2 and r.shape[1] == 3 for r in rows)
    assert len({len(r) for r in rows}) > 1  # ragged
    first = next(l for l in open(example("iea3p4mw_blade_ragged9")) if l.strip() and l[0] != "#")
    assert np.array_equal(rows[0][0], [float(x) for x in first.replace(",", " ").split()])


def test_csv_srows_and_rows_read_the_same(cli, tmp_path):
    rows = sfit.load_rows(example("ship_px121_stations"))
    csv = tmp_path / "ship.csv"
    with open(csv, "w") as f:
        f.write("row,x,y,z\n")
        for j, r in enumerate(rows):
            for p in r:
                f.write(f"{j},{p[0]!r},{p[1]!r},{p[2]!r}\n")
    code, err = run_cli(cli, "pack", example("ship_px121_stations"), "-o", tmp_path / "ship.srows")
    assert code == 0, err
    for other in (sfit.load_rows(str(csv)), sfit.load_rows(str(tmp_path / "ship.srows"))):
        assert len(other) == len(rows)
        assert all(np.array_equal(a, b) for a, b in zip(rows, other))


def test_fit_of_loaded_csv_equals_the_cli_on_it(cli, tmp_path):
    rows = sfit.load_rows(example("d150_wing"))
    csv = tmp_path / "wing.csv"
    with open(csv, "w") as f:
        for r in rows:
            f.writelines(f"{p[0]!r},{p[1]!r},{p[2]!r}\n" for p in r)
            f.write("\n")
    j = cli_fit(cli, tmp_path, csv, "--closed", "u")
    assert_same_surface(sfit.fit(sfit.load_rows(str(csv)), closed="u").surface, j)


def test_step_sections_when_the_build_has_them(cli, tmp_path):
    if "step" not in sfit.output_formats():
        import pytest

        pytest.skip("this build has no STEP exchange (OpenCASCADE); skipped")
    # A STEP file of section curves made by the CLI's own writer from a fit's rows is not at
    # hand; the reader must at least refuse a STEP file without curves with its own code.
    fit = sfit.fit(sfit.load_rows(example("ship_px121_stations")))
    fit.surface.save(str(tmp_path / "hull.step"))
    try:
        sfit.load_rows(str(tmp_path / "hull.step"))
    except sfit.Error as e:
        assert e.code == "input-data"
        code, err = run_cli(cli, "fit", tmp_path / "hull.step", "-o", tmp_path / "x.json")
        assert code == 5 and err.strip() == f"sfit: error: {e}"
    else:
        raise AssertionError("a STEP face without section curves was read as rows")


def test_load_rows_prints_nothing_and_links_no_cli_code(capfd):
    """The readers are the library's (sfit/files.h): reading STEP/IGES sections prints none of
    the CLI's "sfit: ..." lines (the CLI says the file's length unit itself)."""
    import pathlib

    rows = sfit.load_rows(str(pathlib.Path(example("d150_wing")).parents[1] / "tests" /
                              "bad_input" / "closed_sections.igs"))
    assert len(rows) >= 2
    out, err = capfd.readouterr()
    assert out == "" and err == ""
    so = pathlib.Path(sfit._sfit.__file__).read_bytes()
    for cli_symbol in (b"harden_options", b"add_fit_option_flags", b"units_of_outputs"):
        assert cli_symbol not in so
