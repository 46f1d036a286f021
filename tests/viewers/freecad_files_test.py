"""sfit's STEP and IGES files read by FreeCAD (Debian freecad, its freecadcmd), as a CAD user
opens them.

For each case (bundled examples open and closed in u, and generated surfaces closed in v
and in u and v) the CLI writes .step and .igs, and FreeCAD must see: a valid shape with one
face on one non-rational B-spline surface; the degrees, pole counts and periodic flags of
the surface JSON (a periodic direction holds its distinct poles: the JSON's count minus the
degree); and S(u, v) at a grid of parameters equal to sfit's own evaluation (surface_probe)
within 1e-9 of the surface's size. A file stated in metres (--units m) reads as the same
points times 1000 (FreeCAD works in millimetres). The torus as .stl/.obj/.ply in FreeCAD's
Mesh module: the counts, a closed manifold solid, its facets wound outward.
Skips (exit 77) with a message when freecadcmd is not installed.
"""
import json
import math
import os
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import viewer_cases as vc  # noqa: E402

freecad = os.environ.get("SFIT_FREECADCMD") or shutil.which("freecadcmd") or \
    shutil.which("FreeCADCmd")
if not freecad or not os.path.exists(freecad):
    print("SKIPPED: freecadcmd not found; install freecad (scripts/deps/viewers.txt)")
    sys.exit(vc.SKIP)

C = vc.Checks("freecad_files_test")
HERE = os.path.dirname(os.path.abspath(__file__))


def main():
    ws = vc.Workspace()
    cases = [c for c in ws.cases() if c.name != "bump"]
    job, expect, sfit_eval = [], [], {}
    for case in cases:
        ws.fit(case, ["step", "igs"])
        probe = ws.probe(case, 7)
        with open(ws.path(case.name + ".json")) as f:
            surface = json.load(f)
        full = [len(surface["control_points"]), len(surface["control_points"][0])]
        params = [g[:2] for g in probe["grid"]]
        points = [g[2:] for g in probe["grid"]]
        size = max(max(p[k] for p in points) - min(p[k] for p in points) for k in range(3))
        sfit_eval[case.name] = (surface, full, params, points, size)
        for ext in ("step", "igs"):
            job.append({"file": ws.path(f"{case.name}.{ext}"), "parameters": params})
            expect.append((case.name, ext, surface, full, points, size, 1.0))
    # Units: the blade stated in metres reads as the same numbers times 1000 (millimetres).
    blade = next(c for c in cases if c.name == "iea3p4mw_blade_ragged9")
    surface, full, params, points, size = sfit_eval[blade.name]
    for ext in ("step", "igs"):
        out = ws.path(f"blade_in_metres.{ext}")
        vc.run([ws.cli, "fit", blade.rows_path, *blade.closed_flag, "--units", "m", "-o", out])
        job.append({"file": out, "parameters": params})
        expect.append((blade.name, ext + " (--units m)", surface, full, points, size, 1000.0))

    # Meshes in FreeCAD's Mesh module: the torus closed (a solid), wound outward.
    torus = next(c for c in cases if c.name == "torus")
    n = 30
    meshes = []
    for ext in ("stl", "obj", "ply"):
        out = ws.path(f"torus_mesh.{ext}")
        vc.run([ws.cli, "fit", torus.rows_path, *torus.closed_flag, "--mesh-density", str(n),
                "-o", out])
        job.append({"file": out, "mesh": True})
        meshes.append(ext)

    job_path, result_path = ws.path("job.json"), ws.path("result.json")
    with open(job_path, "w") as f:
        json.dump(job, f)
    env = {"PATH": "/usr/bin:/bin", "HOME": os.environ.get("HOME", ws.dir),
           "SFIT_JOB": job_path, "SFIT_RESULT": result_path}
    r = subprocess.run([freecad, os.path.join(HERE, "freecad_check.py")], env=env,
                       capture_output=True, text=True, timeout=240)
    if not C.check(os.path.exists(result_path),
                   f"freecadcmd ran the check (exit {r.returncode}): {r.stdout[-500:]} "
                   f"{r.stderr[-500:]}"):
        C.finish()
    with open(result_path) as f:
        results = json.load(f)

    for ext, got in zip(meshes, results[len(expect):]):
        what = f"torus mesh .{ext} in FreeCAD"
        if not C.check("error" not in got, f"{what}: read ({got.get('error')})"):
            continue
        C.check(got["points"] == n * n and got["facets"] == 2 * n * n,
                f"{what}: {n * n} points, {2 * n * n} facets ({got['points']}, {got['facets']})")
        C.check(got["solid"] and not got["nonmanifold"], f"{what}: a closed solid, manifold")
        C.check(got["signed_volume"] > 0, f"{what}: wound outward (signed volume "
                                          f"{got['signed_volume']:.4g})")
    for (name, ext, surface, full, points, size, scale), got in zip(expect, results):
        what = f"{name}.{ext}"
        if not C.check("error" not in got, f"{what}: FreeCAD read it ({got.get('error')})"):
            continue
        C.check(got["valid"], f"{what}: a valid shape")
        C.check(got["faces"] == 1, f"{what}: one face ({got['faces']})")
        if not C.check(got.get("surface_type") == "BSplineSurface",
                       f"{what}: on a B-spline surface ({got.get('surface_type')})"):
            continue
        C.check(not got["rational"], f"{what}: non-rational")
        C.check(got["degree"] == surface["degree"],
                f"{what}: degrees {got['degree']}, JSON {surface['degree']}")
        # A closed direction on clamped knots (corner knots on closed rows: its first and last
        # columns equal, docs/method.md 7.13) reads back periodic, the two columns as one.
        cp = surface["control_points"]
        clamped = [not surface["periodic"][0] and cp[0] == cp[-1],
                   not surface["periodic"][1] and all(r[0] == r[-1] for r in cp)]
        closed = [surface["periodic"][k] or clamped[k] for k in range(2)]
        C.check(got["periodic"] == closed,
                f"{what}: periodic flags {got['periodic']}, JSON {surface['periodic']}")
        want = [full[k] - (surface["degree"][k] if surface["periodic"][k] else
                           1 if clamped[k] else 0) for k in range(2)]
        C.check(got["poles"] == want, f"{what}: poles {got['poles']}, JSON {full} "
                                      f"(distinct: {want})")
        worst = max(math.dist([scale * c for c in p], q) for p, q in zip(points, got["points"]))
        print(f"{what}: poles {got['poles']}, periodic {got['periodic']}, FreeCAD vs sfit "
              f"{worst / (scale * size):.2g} of the size")
        C.check(worst <= 1e-9 * scale * size,
                f"{what}: FreeCAD's S(u, v) is sfit's within 1e-9 of the size "
                f"({worst / (scale * size):.3g})")
    C.finish()


if __name__ == "__main__":
    main()
