"""Runs inside FreeCAD (freecadcmd), started by freecad_files_test.py: reads each STEP/IGES
file of the job with FreeCAD's own importer and records what FreeCAD sees. The comparison is
the driver's; this only reports. Job and result paths come in SFIT_JOB and SFIT_RESULT."""
import json
import os
import traceback

import Part

job = json.load(open(os.environ["SFIT_JOB"]))
results = []
for item in job:
    r = {"file": item["file"]}
    try:
        shape = Part.read(item["file"])
        r["valid"] = bool(shape.isValid())
        r["faces"] = len(shape.Faces)
        r["solids"] = len(shape.Solids)
        if shape.Faces:
            face = shape.Faces[0]
            s = face.Surface
            r["surface_type"] = type(s).__name__
            if r["surface_type"] == "BSplineSurface":
                r["poles"] = [s.NbUPoles, s.NbVPoles]
                r["periodic"] = [bool(s.isUPeriodic()), bool(s.isVPeriodic())]
                r["degree"] = [s.UDegree, s.VDegree]
                r["rational"] = bool(s.isURational() or s.isVRational())
                r["parameter_range"] = list(s.bounds())
                r["points"] = [list(s.value(u, v)) for u, v in item["parameters"]]
            r["face_range"] = list(face.ParameterRange)
            r["bound_box"] = [shape.BoundBox.XMin, shape.BoundBox.YMin, shape.BoundBox.ZMin,
                              shape.BoundBox.XMax, shape.BoundBox.YMax, shape.BoundBox.ZMax]
    except Exception:
        r["error"] = traceback.format_exc()
    results.append(r)
with open(os.environ["SFIT_RESULT"], "w") as f:
    json.dump(results, f)
