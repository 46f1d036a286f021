"""The FreeCAD workbench (integrations/freecad) in FreeCAD's own freecadcmd, in a clean
environment (PATH and a fresh HOME only), as a user's FreeCAD runs it.

Stage "fit" (fc_fit_stage.py): closed sections from sketches (circles with a radius
constraint and a rounded rectangle of lines and arcs), open sections from sketches (a B-spline
and a line each), rows of point objects, and a .rows file, each fitted by a SurfaceFit
feature. Checked here: one valid face (isValid and Part's check, BRepCheck); a non-rational
B-spline whose degrees, periodic flags, knots and poles equal, exactly, the JSON surface of
the sfit CLI fitted to the same rows with the same options; every data point within T by
FreeCAD's distToShape (within |T|, the Euclidean length of the per-axis T) and, per axis, by
FreeCAD's evaluation at sfit's parameters; closed contours detected (u closed for the rings).
A sketch edited (a radius constraint 12 -> 15) and recomputed refits: the poles change,
every point within T again and the poles equal the CLI's for the edited rows.
Eight circles around an axis, the first selected again at the end, are detected closed in u
and v. Four edges picked on a placed box (SourceEdges) are four rows.
A missing source file and a single section fail the feature with a message.
Stage "reopen": the saved document opened in a new freecadcmd, the module found through the
FreeCAD parameter instead: every feature there with its proxy class and sources, its saved
shape the one fitted, and a recompute gives the same poles.
Skips (exit 77) only when freecadcmd is absent.
"""
import json
import os
import shutil
import subprocess
import sys
import tempfile

SKIP = 77
HERE = os.path.dirname(os.path.abspath(__file__))
freecad = os.environ.get("SFIT_FREECADCMD") or shutil.which("freecadcmd")
if not freecad or not os.path.exists(freecad):
    print("SKIPPED: freecadcmd not found; install freecad (scripts/deps/viewers.txt)")
    sys.exit(SKIP)
CLI = os.environ["SFIT_CLI"]
failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        failures.append(what)
    return ok


def run_stage(stage, out, extra=None):
    job = {"stage": stage, "out": out, "workbench": os.path.dirname(HERE),
           "python": os.environ["SFIT_PYTHON_DIR"], "examples": os.environ["SFIT_EXAMPLES"]}
    job.update(extra or {})
    path = os.path.join(out, f"job_{stage}.json")
    with open(path, "w") as f:
        json.dump(job, f)
    env = {"PATH": "/usr/bin:/bin", "HOME": os.path.join(out, "home"), "SFIT_JOB": path}
    os.makedirs(env["HOME"], exist_ok=True)
    r = subprocess.run([freecad, os.path.join(HERE, "fc_fit_stage.py")], env=env,
                       capture_output=True, text=True, timeout=240)
    res = os.path.join(out, f"result_{stage}.json")
    if not check(os.path.exists(res), f"freecadcmd ran stage {stage}"):
        print(f"exit {r.returncode}:\n{r.stdout[-2000:]}\n{r.stderr[-2000:]}")
        finish()
    with open(res) as f:
        results = json.load(f)
    for e in results["errors"]:
        check(False, f"stage {stage}: {e}")
    return results


def finish():
    print(f"{len(failures)} failure(s)" if failures else "all checks passed")
    sys.exit(1 if failures else 0)


def cli_surface(case, out):
    """The sfit CLI's JSON surface for the rows the feature fitted, with its options."""
    o = case["options"]
    args = [CLI, "fit", case["rows_file"], "-q", "--degree", str(o["degree"])]
    if "tol" in o:
        args += ["--tol", repr(o["tol"])]
    else:
        args += ["--tol-rel", repr(o["tol_rel"])]
    args += ["--closed", case["closed"] or "none"]
    for k in ("parameters", "search", "method"):
        if k in o:
            args += [f"--{k}", o[k]]
    path = case["rows_file"][:-5] + ".json"
    args += ["-o", path]
    r = subprocess.run(args, capture_output=True, text=True, timeout=120)
    if not check(r.returncode == 0, f"sfit CLI fitted {case['rows_file']}: {r.stderr.strip()}"):
        return None
    with open(path) as f:
        return json.load(f)


def same_as_cli(name, got, js):
    """FreeCAD's surface equals the JSON surface exactly: degrees, periodic flags, distinct
    poles, knots (the domain's distinct knots, multiplicities of the full vector)."""
    check(got["degree"] == js["degree"], f"{name}: degrees {got['degree']} = JSON {js['degree']}")
    check(got["periodic"] == js["periodic"],
          f"{name}: periodic {got['periodic']} = JSON {js['periodic']}")
    cp = js["control_points"]
    p, q = js["degree"]
    nu = len(cp) - (p if js["periodic"][0] else 0)
    nv = len(cp[0]) - (q if js["periodic"][1] else 0)
    want = [[cp[i][j] for j in range(nv)] for i in range(nu)]
    check(got["poles"] == want, f"{name}: FreeCAD's {len(got['poles'])} x "
                                f"{len(got['poles'][0])} poles equal the JSON's distinct "
                                f"{nu} x {nv} exactly")
    for key, knots, deg, per, n in (("u", js["knots_u"], p, js["periodic"][0], len(cp)),
                                    ("v", js["knots_v"], q, js["periodic"][1], len(cp[0]))):
        dom = knots[deg:n + 1]
        distinct = sorted(set(dom))
        check(got[key + "knots"] == distinct, f"{name}: {key} knots {got[key + 'knots']} = "
                                              f"the JSON domain's {distinct}")
        if not per:
            mults = [knots.count(k) for k in distinct]
            check(got[key + "mults"] == mults, f"{name}: {key} multiplicities")
    return got["poles"] == want


def check_case(name, case, out, closed=None):
    if not check("error" not in case, f"{name}: fitted ({case.get('error', '')})"):
        return
    check(case["valid"] and case["faces"] == 1, f"{name}: one valid face (isValid)")
    check(case["check"] == "ok", f"{name}: Part's check (BRepCheck) passes: {case['check']}")
    check(case["type"] == "BSplineSurface" and not case["rational"],
          f"{name}: a non-rational B-spline surface ({case['type']})")
    check(case["within"], f"{name}: the report says within T")
    eps = 1e-9 * max(1.0, case["norm_T"])
    check(case["max_dist"] <= case["norm_T"] + eps,
          f"{name}: every one of {case['points']} points within |T| = {case['norm_T']:.4g} "
          f"by FreeCAD's distToShape (largest {case['max_dist']:.4g})")
    check(all(d <= t * (1 + 1e-9) + 1e-12 for d, t in zip(case["max_axis"], case["tolerance"])),
          f"{name}: per axis by FreeCAD's evaluation at sfit's parameters "
          f"{[round(d, 6) for d in case['max_axis']]} <= T {case['tolerance']}")
    if closed is not None:
        check(case["closed"] == closed, f"{name}: closed directions detected "
                                        f"'{case['closed']}' (want '{closed}')")
    js = cli_surface(case, out)
    if js is not None:
        same_as_cli(name, case, js)
    print(f"{name}: {case['control_points']} control points, {case['points']} points, "
          f"largest |d| per axis {case['report_max']}, T {case['tolerance']}")


def pole_diff(a, b):
    """Largest coordinate difference of two pole nets; infinite when their counts differ."""
    if len(a) != len(b) or any(len(x) != len(y) for x, y in zip(a, b)):
        return float("inf")
    return max(abs(p - q) for ca, cb in zip(a, b) for pa, pb in zip(ca, cb)
               for p, q in zip(pa, pb))


def install_check(out):
    """cmake --install into a temporary prefix; FreeCAD (its user Mod folder linked to the
    installed workbench) finds the workbench and, through it, the installed module."""
    build = os.environ.get("SFIT_BUILD_DIR")
    if not check(bool(build), "SFIT_BUILD_DIR given (the build tree to install)"):
        return
    prefix = os.path.join(out, "prefix")
    r = subprocess.run(["cmake", "--install", build, "--prefix", prefix], capture_output=True,
                       text=True, timeout=120)
    if not check(r.returncode == 0, f"cmake --install {build} --prefix {prefix}: "
                                    f"{r.stderr[-400:]}"):
        return
    wb = os.path.join(prefix, "share", "freecad", "Mod", "Sfit")
    mod = os.path.join(prefix, "lib", "python3", "dist-packages", "sfit")
    check(os.path.exists(os.path.join(wb, "package.xml")) and
          os.path.exists(os.path.join(wb, "sfit_freecad", "feature.py")),
          f"the workbench installed in {wb}")
    check(any(f.startswith("_sfit") for f in os.listdir(mod)) if os.path.isdir(mod) else False,
          f"the module installed in {mod}")
    home = os.path.join(out, "home_install")
    user_mod = os.path.join(home, ".local", "share", "FreeCAD", "Mod")
    os.makedirs(user_mod)
    os.symlink(wb, os.path.join(user_mod, "Sfit"))
    res = os.path.join(out, "result_install.json")
    env = {"PATH": "/usr/bin:/bin", "HOME": home, "SFIT_RESULT": res}
    subprocess.run([freecad, os.path.join(HERE, "fc_install_stage.py")], env=env,
                   capture_output=True, text=True, timeout=120)
    got = json.load(open(res)) if os.path.exists(res) else {"error": "no result"}
    found = os.path.realpath(got.get("sfit", "/nowhere"))
    check("error" not in got and got.get("sys_path_has_mod") and
          found.startswith(os.path.realpath(mod) + os.sep),
          f"FreeCAD loaded the installed workbench and it found the installed module "
          f"({got.get('sfit')}) {got.get('error', '')}")


def main():
    out = tempfile.mkdtemp(prefix="sfit_freecad_wb_")
    fit = run_stage("fit", out)
    cases = fit["cases"]
    for name, closed in (("RingFit", "u"), ("WingFit", ""), ("ScanFit", ""), ("ShipFit", ""),
                         ("ShipSfit01", ""), ("EdgeFit", ""), ("TorusFit", "uv"),
                         ("RingFit_edited", "u"), ("RingFit_moved", "u")):
        if check(name in cases, f"{name}: recorded"):
            check_case(name, cases[name], out, closed)
    for ext, x in fit.get("export", {}).items():
        check("error" not in x and x["faces"] == 1 and x["type"] == "BSplineSurface" and
              x["same_counts"] and x["max_pole_diff"] <= 1e-9,
              f"FreeCAD's own {ext.upper()} export of the feature reads back as one B-spline "
              f"face with its poles (largest difference {x.get('max_pole_diff')}) "
              f"{x.get('error', '')}")
    check(len(fit.get("export", {})) == 2, "exported as STEP and IGES")
    check(fit.get("edge_count") == 4 and cases.get("EdgeFit", {}).get("rows_count") == 4,
          f"EdgeFit: the four vertical edges picked on a placed box are four rows "
          f"({fit.get('edge_count')}, {cases.get('EdgeFit', {}).get('rows_count')})")
    for name, want in (("MissingFile", "no such file"), ("OneSection", "2 rows")):
        f = fit.get("faults", {}).get(name, {})
        check("Invalid" in f.get("state", []) and want in (f.get("message") or ""),
              f"{name}: the feature fails with a message ({f.get('message')}, {f.get('state')})")
    e = fit.get("edit", {})
    check(e.get("sketch_radius") == 15.0, f"the sketch's radius constraint edited to 15 "
                                          f"({e.get('sketch_radius')})")
    check(e.get("sketch_touched") and (e.get("recomputed") or 0) >= 2,
          f"editing the sketch touched it; one recompute ran it and the feature "
          f"({e.get('recomputed')} objects)")
    check(e.get("poles_changed"), "the recompute after the edit refitted (the poles changed)")
    if "RingFit" in cases and "RingFit_edited" in cases:
        check(cases["RingFit"]["tolerance"] == cases["RingFit_edited"]["tolerance"],
              "the edit kept T (absolute)")
        check(cases["RingFit_moved"]["poles"] != cases["RingFit_edited"]["poles"],
              "moving a section refitted (the poles changed)")
    if "saved" not in fit:
        finish()
    again = run_stage("reopen", out, {"saved": fit["saved"]})
    final = {"RingFit": "RingFit_moved", "WingFit": "WingFit", "ScanFit": "ScanFit",
             "ShipFit": "ShipFit", "EdgeFit": "EdgeFit"}
    for name, r in again.get("reopened", {}).items():
        check(r["exists"], f"reopened: {name} is in the saved document")
        check(r["proxy"] == "sfit_freecad.feature.SurfaceFit",
              f"reopened: {name}'s proxy is restored ({r['proxy']})")
        before = cases[final[name]]["poles"]
        saved = r["saved"]
        scale = max(abs(c) for col in before for p in col for c in p)
        saved, refit = r["saved"], r["refit"]
        check(saved["valid"] and pole_diff(saved["poles"], before) <= 1e-12 * scale,
              f"reopened: {name}'s saved face is the fitted one (poles within "
              f"{pole_diff(saved['poles'], before):.3g} of a size {scale:.3g})")
        # The sketches come back from the file's text (FreeCAD writes their numbers as text),
        # so the refit is compared within 5e-8 of the size, not bit for bit: the geometric
        # rule's parameters come from projections (a few Newton steps each), which carry the
        # text's round-off into the poles at some 5e-9 of the size.
        check(pole_diff(refit["poles"], before) <= 5e-8 * scale and r["within"] and
              not any(s in r["state"] for s in ("Invalid", "Error")),
              f"reopened: {name} recomputed refits to the same poles (within "
              f"{pole_diff(refit['poles'], before):.3g}), within T")
    check(len(again.get("reopened", {})) == 5, "reopened: five features")
    install_check(out)
    shutil.rmtree(out, ignore_errors=True) if not failures else print(f"kept {out}")
    finish()


if __name__ == "__main__":
    main()
