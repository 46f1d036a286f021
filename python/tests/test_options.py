"""The library's option table (sfit.fit_options(), include/sfit/options.h) is what every front
end offers: each option is a flag of `sfit fit --help` with the table's help, a keyword of
sfit.fit() (group "fit") or of save() (group "output") with the table's default, and in
docs/cli.md and docs/options.md."""
import re
import subprocess

import numpy as np
import pytest

import sfit
from conftest import REPO, wavy_grid

TABLE = sfit.fit_options()
FIT = [o for o in TABLE if o["group"] == "fit"]
OUTPUT = [o for o in TABLE if o["group"] == "output"]
# Every option `sfit fit` has; the table must hold them all (a new flag of the CLI that is not
# in the table fails test_every_flag_of_sfit_fit_is_in_the_table).
EXPECTED = {"degree", "degree_u", "degree_v", "tol", "tol_rel", "closed", "search", "parameters",
            "knots",
            "method", "norm", "seam", "orient", "fold_guard", "rerepresent", "threads", "mesh",
            "obj_freeform", "mesh_density", "normals", "fields", "units"}


def ids(options):
    return [o["name"] for o in options]


@pytest.fixture(scope="module")
def fit_help(cli):
    return subprocess.run([cli, "fit", "--help"], capture_output=True, text=True,
                          check=True).stdout


@pytest.fixture(scope="module")
def grid():
    return wavy_grid(12, 15)


def test_the_table_has_every_option():
    assert {o["name"] for o in TABLE} == EXPECTED
    for o in TABLE:
        assert o["type"] in {"integer", "number", "tolerance", "choice", "flag"}
        if o["type"] == "choice":
            assert o["default"] in o["choices"]
        if o["type"] in {"integer", "number"}:
            assert o["min"] <= o["max"]


def help_entries(text):
    """`sfit fit --help` as one string per option (CLI11 puts a long flag's help on the next
    line)."""
    entries = []
    for line in text.splitlines():
        if re.match(r"\s+-", line):
            entries.append(line.strip())
        elif entries and line.startswith("        ") and line.strip():
            entries[-1] += " " + line.strip()
    return entries


@pytest.mark.parametrize("option", TABLE, ids=ids(TABLE))
def test_each_option_is_in_sfit_fit_help_with_the_tables_help(option, fit_help):
    entries = [e for e in help_entries(fit_help) if re.match(re.escape(option["flag"]) + r"(\s|$)", e)]
    assert len(entries) == 1, f"{option['flag']} not in `sfit fit --help`"
    entry = entries[0]
    assert option["help"] in entry
    if option["default"] is not None and option["type"] != "flag":
        assert f"(default {option['default']})" in entry
    if option["type"] == "choice" and option["group"] == "fit":
        assert "{" + ",".join(option["choices"]) + "}" in entry  # CLI11's check, the table's


def test_every_flag_of_sfit_fit_is_in_the_table(fit_help):
    # The flags before the picture options, besides input/output/report/quiet/help.
    options = fit_help.split("\nPicture")[0]
    flags = set(re.findall(r"^\s+(?:-\w,)?(--[a-z][a-z0-9-]*)", options, re.M))
    assert flags - {o["flag"] for o in TABLE} == {"--help", "--output", "--report", "--quiet"}


@pytest.mark.parametrize("option", FIT, ids=ids(FIT))
def test_each_fit_option_is_a_keyword_with_the_tables_default(option, grid):
    name, default = option["name"], option["default"]
    base = sfit.fit(grid, tol=0.01)
    # Given its default (None where the table's depends on the data), the fit is the default's.
    kwargs = {name: default}
    if name in ("tol", "tol_rel"):
        base = sfit.fit(grid)  # 1e-3 of the diagonal
    else:
        kwargs["tol"] = 0.01
    f = sfit.fit(grid, **kwargs)
    assert f.surface.control_points.tolist() == base.surface.control_points.tolist()
    assert (f.surface.degree_u, f.surface.degree_v) == (base.surface.degree_u,
                                                        base.surface.degree_v)


def other_value(option):
    t = option["type"]
    if t == "choice":
        return next(c for c in option["choices"] if c not in (option["default"], "known"))
    if t == "flag":
        return not option["default"]
    if t == "integer":
        return 2
    if t == "number":
        return 0.01
    return (0.01, 0.01, 0.02)


@pytest.mark.parametrize("option", FIT, ids=ids(FIT))
def test_each_fit_option_takes_another_allowed_value(option, grid):
    name = option["name"]
    kwargs = {name: other_value(option)}
    if name != "tol_rel" and name != "tol":
        kwargs["tol"] = 0.05
    try:
        sfit.fit(grid, **kwargs)
    except sfit.Error as e:  # a fit may miss T; a refused keyword is a usage error
        assert e.code != "usage", str(e)


@pytest.mark.parametrize("option", [o for o in FIT if o["type"] == "choice"],
                         ids=ids([o for o in FIT if o["type"] == "choice"]))
def test_a_bad_value_names_every_allowed_value(option, grid):
    with pytest.raises(sfit.Error) as e:
        sfit.fit(grid, **{option["name"]: "bogus"})
    assert e.value.code == "usage" and e.value.option == option["name"]
    assert e.value.message == "'bogus' is not one of " + ", ".join(option["choices"])


def test_parameters_default_is_the_librarys_auto():
    assert next(o for o in TABLE if o["name"] == "parameters")["default"] == "auto"


def save_defaults(method):
    """save()'s keyword defaults, as repr, from its signature."""
    import inspect
    return {name: repr(p.default) for name, p in inspect.signature(method).parameters.items()
            if p.default is not inspect.Parameter.empty}


@pytest.mark.parametrize("method", [sfit.Surface.save, sfit.Fit.save], ids=["Surface", "Fit"])
def test_each_output_option_is_a_save_keyword_with_the_tables_default(method):
    defaults = save_defaults(method)
    for o in OUTPUT:
        assert o["name"] in defaults, f"save() has no keyword {o['name']}"
        assert defaults[o["name"]] == repr(o["default"]), o["name"]


def test_save_keywords_change_the_file(grid, tmp_path):
    f = sfit.fit(grid, tol=0.01)
    f.save(str(tmp_path / "a.obj"))
    f.save(str(tmp_path / "b.obj"), **{o["name"]: o["default"] for o in OUTPUT})
    f.save(str(tmp_path / "c.obj"), obj_freeform=True)
    f.save(str(tmp_path / "d.obj"), normals="flip")
    a, b, c, d = ((tmp_path / n).read_text() for n in ("a.obj", "b.obj", "c.obj", "d.obj"))
    assert a == b
    assert re.search(r"^surf ", c, re.M) and not re.search(r"^surf ", a, re.M)  # free-form
    assert d != a
    with pytest.raises(sfit.Error) as e:
        f.save(str(tmp_path / "e.obj"), normals="inward")
    assert e.value.option in ("normals", "--normals")
    assert not (tmp_path / "e.obj").exists()


@pytest.mark.parametrize("doc", ["cli.md", "options.md"])
def test_each_option_is_in_the_docs(doc):
    text = (REPO / "docs" / doc).read_text()
    for o in TABLE:
        assert o["flag"] in text, f"{o['flag']} not in docs/{doc}"
        assert o["help"].replace("|", "\\|") in text if doc == "options.md" else o["help"] in text


def test_unknown_keyword_lists_the_tables_options(grid):
    # fit()'s signature refuses an unknown keyword (TypeError, as Python does); the compiled
    # function behind it names the table's options, and a save() option as such.
    with pytest.raises(TypeError):
        sfit.fit(grid, no_such_option=1)
    native = sfit.fit.__globals__["_native"]
    with pytest.raises(sfit.Error) as e:
        native(grid, None, no_such_option=1)
    for o in FIT:
        assert o["name"] in e.value.message
    with pytest.raises(sfit.Error) as e:
        native(grid, None, normals="flip")  # a save() option
    assert "save()" in e.value.message
