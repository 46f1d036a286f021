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
        if item.get("mesh"):  # FreeCAD's Mesh module: counts, solidity, the facets' winding
            import Mesh
            m = Mesh.Mesh(item["file"])
            r["points"], r["facets"] = m.CountPoints, m.CountFacets
            r["solid"], r["nonmanifold"] = bool(m.isSolid()), bool(m.hasNonManifolds())
            pts = [(p.x, p.y, p.z) for p in m.Points]
            c = [sum(p[k] for p in pts) / len(pts) for k in range(3)]
            size = max(max(abs(p[k] - c[k]) for p in pts) for k in range(3))
            vol = 0.0
            for f in m.Facets:  # six times the signed volume, centred and scaled
                a, b, d = ([(q[k] - c[k]) / size for k in range(3)] for q in f.Points)
                vol += (a[0] * (b[1] * d[2] - b[2] * d[1]) - a[1] * (b[0] * d[2] - b[2] * d[0]) +
                        a[2] * (b[0] * d[1] - b[1] * d[0]))
            r["signed_volume"] = vol / 6
            results.append(r)
            continue
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
