"""The workbench in FreeCAD's GUI under Xvfb, installed as a user installs it: a fresh HOME
whose FreeCAD Mod folder (~/.local/share/FreeCAD/Mod/Sfit) links to integrations/freecad, the
sfit module found through SFIT_PYTHONPATH. fc_gui_stage.py draws five ring sections, selects
them and runs the command "Fit surface". Checked: FreeCAD found the workbench and its command;
the feature was made, within T; the task panel is open and shows the report; the data points
are drawn coloured (as many as were fitted) and the worst-point marker sits on the worst
point; changing the tolerance in the panel refits at once and its report follows; a screenshot
of the window (task panel and fitted face) was written.

    gui_test.py [--screenshot docs/freecad.png]

Skips (exit 77) only when freecad or xvfb-run is absent.
"""
import argparse
import json
import os
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        failures.append(what)
    return ok


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--screenshot", help="where to write the PNG (default: a temporary folder)")
    args = ap.parse_args()
    freecad = os.environ.get("SFIT_FREECAD") or shutil.which("freecad")
    xvfb = shutil.which("xvfb-run")
    if not freecad or not xvfb:
        print("SKIPPED: freecad or xvfb-run not found (scripts/deps/viewers.txt)")
        sys.exit(77)
    out = tempfile.mkdtemp(prefix="sfit_freecad_gui_")
    home = os.path.join(out, "home")
    mod = os.path.join(home, ".local", "share", "FreeCAD", "Mod")
    os.makedirs(mod)
    os.symlink(os.path.dirname(HERE), os.path.join(mod, "Sfit"))
    shot = os.path.abspath(args.screenshot) if args.screenshot else os.path.join(out, "shot.png")
    job = os.path.join(out, "job.json")
    with open(job, "w") as f:
        json.dump({"out": out, "screenshot": shot}, f)
    env = {"PATH": "/usr/bin:/bin", "HOME": home, "SFIT_JOB": job,
           "SFIT_PYTHONPATH": os.environ["SFIT_PYTHON_DIR"],
           # Qt WebEngine (FreeCAD's start page) refuses to start as root with its sandbox
           "QTWEBENGINE_DISABLE_SANDBOX": "1"}
    r = subprocess.run([xvfb, "-a", "-s", "-screen 0 1400x900x24", freecad,
                        os.path.join(HERE, "fc_gui_stage.py")], env=env, capture_output=True,
                       text=True, timeout=240)
    res = os.path.join(out, "result_gui.json")
    if not check(os.path.exists(res), "FreeCAD's GUI ran the stage"):
        print(f"exit {r.returncode}:\n{r.stdout[-2000:]}\n{r.stderr[-2000:]}")
        sys.exit(1)
    with open(res) as f:
        g = json.load(f)
    for e in g["errors"]:
        check(False, e)
    check("SfitWorkbench" in g.get("workbenches", []),
          "FreeCAD found the workbench in the user Mod folder")
    check(g.get("command"), "the command Sfit_FitSurface is registered")
    check(g.get("feature") and g.get("within"),
          f"the command made the feature, within T ({g.get('control_points')} control points)")
    check(g.get("task_panel_open") and g.get("panel_found"), "the task panel is open")
    text = " ".join(g.get("panel_text", []))
    check("Control points" in text and "Within T" in text and "Worst point" in text,
          "the task panel shows the report")
    check(g.get("view_provider") == "ViewProviderSurfaceFit" and
          g.get("deviation_points_shown") == g.get("data_points") and
          g.get("deviation_switch") == 0,
          f"the deviation display shows the {g.get('data_points')} data points "
          f"({g.get('deviation_points_shown')})")
    check(g.get("worst_marker") and g.get("worst_point") and
          max(abs(a - b) for a, b in zip(g["worst_marker"], g["worst_point"])) < 1e-4,
          "the worst-point marker is at the worst point")
    c = g.get("coarse", {})
    check(c.get("mode") == "Absolute" and c.get("T") == [0.5, 0.5, 0.5] and c.get("within") and
          c.get("control_points") != g.get("control_points") and
          c.get("control_points", "?") in c.get("report", "") and
          g.get("fine_again") == g.get("control_points"),
          f"the panel refits at once: absolute T = 0.5 gives {c.get('control_points')}, shown "
          f"in its report; relative again gives {g.get('fine_again')} again")
    check(os.path.exists(shot) and os.path.getsize(shot) > 20000,
          f"screenshot written: {shot} ({g.get('size')})")
    print(f"{len(failures)} failure(s)" if failures else "all checks passed")
    if not failures:
        shutil.rmtree(out, ignore_errors=True)
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
