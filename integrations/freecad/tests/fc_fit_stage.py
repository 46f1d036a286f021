"""Runs inside freecadcmd (started by workbench_test.py in a clean environment): builds
sections as FreeCAD users do (sketches, point objects, a .rows file), fits them with the
workbench's SurfaceFit feature, and records what FreeCAD sees. The job (a JSON file named by
SFIT_JOB) gives the workbench folder, the sfit module folder and the output folder; both
folders go on sys.path here, since the clean environment has no PYTHONPATH.

Stage "fit": the cases, one sketch edited and recomputed, the document saved.
Stage "reopen": the saved document opened again, its features checked and refitted.
"""
import json
import math
import os
import sys
import traceback

job = json.load(open(os.environ["SFIT_JOB"]))
sys.path.insert(0, job["workbench"])
os.environ["SFIT_PYTHONPATH"] = job["python"]  # found by sfit_freecad.locate, as documented

import FreeCAD as App  # noqa: E402
import Part  # noqa: E402

from sfit_freecad import feature  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from sections import closed_sections, open_sections, point_rows, torus_sections  # noqa: E402

V = App.Vector
results = {"cases": {}, "errors": []}


def shape_record(obj):
    """What FreeCAD sees of the feature's shape."""
    shape = obj.Shape
    r = {"valid": bool(shape.isValid()), "faces": len(shape.Faces)}
    try:
        shape.check(True)  # BRepCheck_Analyzer (and BOP checks); raises on a fault
        r["check"] = "ok"
    except Exception as e:  # noqa: BLE001 - the message is the record
        r["check"] = str(e)
    s = shape.Faces[0].Surface
    r["type"] = type(s).__name__
    r["degree"] = [s.UDegree, s.VDegree]
    r["periodic"] = [bool(s.isUPeriodic()), bool(s.isVPeriodic())]
    r["rational"] = bool(s.isURational() or s.isVRational())
    r["poles"] = [[list(p) for p in col] for col in s.getPoles()]
    r["uknots"], r["vknots"] = list(s.getUKnots()), list(s.getVKnots())
    r["umults"], r["vmults"] = list(s.getUMultiplicities()), list(s.getVMultiplicities())
    return r


def deviation_record(obj, name):
    """Every data point against the face by FreeCAD's own measures: distToShape (Euclidean,
    to the nearest point of the face), and per axis S(u_i, v_i) - p_i with FreeCAD's own
    evaluation at the parameters sfit gave the point."""
    res = feature.fit_feature(obj)
    fit = res["fit"]
    face = obj.Shape.Faces[0]
    surf = face.Surface
    tol = [float(x) for x in fit.report["tolerance"]]
    worst_dist, worst_axis = 0.0, [0.0, 0.0, 0.0]
    vs = [float(v) for v in fit.v_points]  # each point's own v (parameters geometric)
    if not vs:
        for v, n in zip(fit.v, fit.row_sizes):
            vs += [float(v)] * int(n)
    for p, u, v in zip(fit.points, fit.u, vs):
        pt = V(*[float(c) for c in p])
        worst_dist = max(worst_dist, Part.Vertex(pt).distToShape(face)[0])
        q = surf.value(float(u), float(v))
        for k in range(3):
            worst_axis[k] = max(worst_axis[k], abs(q[k] - pt[k]))
    rows_path = os.path.join(job["out"], name + ".rows")
    with open(rows_path, "w") as f:  # the rows fitted, every double exactly (repr)
        for row in res["rows"]:
            f.write("\n".join(" ".join(repr(float(c)) for c in p) for p in row) + "\n\n")
    return {"tolerance": tol, "norm_T": math.sqrt(sum(t * t for t in tol)),
            "max_dist": worst_dist, "max_axis": worst_axis, "points": len(fit.points),
            "rows_file": rows_path, "rows_count": len(res["rows"]), "closed": res["closed"], "options": res["options"],
            "report_max": [float(x) for x in fit.report["max_deviation"]],
            "within": bool(obj.WithinTolerance), "control_points": obj.ControlPoints}


def record(name, obj):
    r = {"state": list(obj.State)}
    try:
        r.update(shape_record(obj))
        r.update(deviation_record(obj, name))
    except Exception:  # noqa: BLE001
        r["error"] = traceback.format_exc()
    results["cases"][name] = r


def export_record(obj):
    """File > Export's own path: FreeCAD's Import module writes STEP and IGES; Part.read
    reads them back."""
    import Import
    out = {}
    poles = obj.Shape.Faces[0].Surface.getPoles()
    for ext in ("step", "igs"):
        path = os.path.join(job["out"], obj.Name + "." + ext)
        try:
            Import.export([obj], path)
            back = Part.read(path)
            s = back.Faces[0].Surface
            got = s.getPoles()
            same_shape = len(got) == len(poles) and len(got[0]) == len(poles[0])
            diff = max((got[i][j] - poles[i][j]).Length for i in range(len(poles))
                       for j in range(len(poles[0]))) if same_shape else None
            out[ext] = {"faces": len(back.Faces), "type": type(s).__name__,
                        "same_counts": same_shape, "max_pole_diff": diff}
        except Exception:  # noqa: BLE001
            out[ext] = {"error": traceback.format_exc()}
    return out


def stage_fit():
    doc = App.newDocument("sfit_workbench_test")
    rings = closed_sections(doc)
    wings = open_sections(doc)
    scans = point_rows(doc)
    doc.recompute()
    a = feature.create(doc, rings, name="RingFit", ToleranceMode="Absolute", Tolerance=0.05)
    b = feature.create(doc, wings, name="WingFit", ToleranceRelative=2e-3)
    c = feature.create(doc, scans, name="ScanFit", ToleranceMode="Absolute", Tolerance=0.01)
    d = feature.create(doc, [], os.path.join(job["examples"], "ship_px121_stations.rows"),
                       name="ShipFit")
    d1 = feature.create(doc, [], os.path.join(job["examples"], "ship_px121_stations.rows"),
                        name="ShipSfit01", Method="sfit01")  # the paper's two stages
    box = doc.addObject("Part::Box", "Block")
    box.Length, box.Width, box.Height = 30, 20, 10
    box.Placement = App.Placement(V(100, 0, 0), App.Rotation(V(0, 0, 1), 30))
    doc.recompute()
    vertical = [f"Edge{i + 1}" for i, e in enumerate(box.Shape.Edges)
                if abs(e.Vertexes[0].Point.z - e.Vertexes[1].Point.z) > 1]
    e = feature.create(doc, [], name="EdgeFit", edges=[(box, n) for n in vertical],
                       ToleranceMode="Absolute", Tolerance=0.01, Degree=2)
    results["edge_count"] = len(vertical)
    tube = torus_sections(doc)
    doc.recompute()
    t = feature.create(doc, tube + tube[:1], name="TorusFit", ToleranceMode="Absolute",
                       Tolerance=0.02)  # the first section again at the end: closed in v
    doc.recompute()
    for o in (a, b, c, d, d1, e, t):
        record(o.Name, o)
    before = shape_record(a)["poles"]
    results["export"] = export_record(a)
    # Edit a sketch: the radius of the second ring, 12 -> 15; recompute refits.
    rings[1].setDatum(0, App.Units.Quantity("15 mm"))
    touched = "Touched" in rings[1].State
    recomputed = doc.recompute()
    record("RingFit_edited", a)
    results["edit"] = {"sketch_touched": bool(touched), "recomputed": recomputed,
                       "poles_changed": shape_record(a)["poles"] != before,
                       "sketch_radius": rings[1].Geometry[0].Radius}
    # Move a section: the last ring up by 5.
    rings[4].Placement = App.Placement(V(0, 0, 45), App.Rotation())
    doc.recompute()
    record("RingFit_moved", a)
    # Faults: a missing file, a single section: the feature fails with a message.
    faults = {}
    for name, kw in (("MissingFile", {"source_file": "/nonexistent/sections.rows"}),
                     ("OneSection", {"sources": rings[:1]})):
        bad = feature.create(doc, name=name, **kw)
        doc.recompute()
        try:
            feature.fit_feature(bad)
            message = None
        except Exception as e:  # noqa: BLE001
            message = str(e)
        faults[name] = {"state": list(bad.State), "message": message}
        doc.removeObject(bad.Name)
    results["faults"] = faults
    path = os.path.join(job["out"], "fitted.FCStd")
    doc.saveAs(path)
    results["saved"] = path


def stage_reopen():
    App.ParamGet(  # the documented parameter, the second way the workbench finds sfit
        "User parameter:BaseApp/Preferences/Mod/Sfit").SetString("ModulePath", job["python"])
    del os.environ["SFIT_PYTHONPATH"]
    doc = App.openDocument(job["saved"])
    names = ["RingFit", "WingFit", "ScanFit", "ShipFit", "EdgeFit"]
    reopened = {}
    for n in names:
        o = doc.getObject(n)
        reopened[n] = {"exists": o is not None,
                       "proxy": type(o.Proxy).__module__ + "." + type(o.Proxy).__name__
                       if o is not None and o.Proxy is not None else None,
                       "sources": [s.Name for s in o.Sources] if o is not None else [],
                       "saved": shape_record(o) if o is not None else None}
    for n in names:
        o = doc.getObject(n)
        o.touch()
    doc.recompute()
    for n in names:
        o = doc.getObject(n)
        reopened[n]["refit"] = shape_record(o)
        reopened[n]["state"] = list(o.State)
        reopened[n]["within"] = bool(o.WithinTolerance)
    results["reopened"] = reopened


try:
    stage_fit() if job["stage"] == "fit" else stage_reopen()
except Exception:  # noqa: BLE001
    results["errors"].append(traceback.format_exc())
with open(os.path.join(job["out"], f"result_{job['stage']}.json"), "w") as f:
    json.dump(results, f)
