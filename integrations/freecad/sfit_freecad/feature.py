"""The parametric feature "SurfaceFit" (headless: FreeCAD and Part only, no GUI).

A Part::FeaturePython whose Shape is one Part face on the B-spline surface sfit fits to the
rows of its sources. Its sources are links (PropertyLinkList), so editing a sketch or moving
a section marks it for recompute, and the recompute refits. The proxy class lives in this
module (sfit_freecad.feature.SurfaceFit): a saved document reopens wherever the workbench
is installed.
"""
import os

import numpy as np

import FreeCAD
import Part

from . import rows as rows_mod
from .locate import find_sfit

GROUP = "Sfit"
REPORT = "Sfit report"
DATA = "Sfit data"
CLOSED_CHOICES = ["Auto", "None", "U", "V", "UV"]
TOLERANCE_MODES = ["Relative", "Absolute"]
METHODS = ["surface", "sfit01"]
PARAMETERS = ["auto", "paper", "uniform", "chord", "centripetal", "fewest"]
SEARCHES = ["fast", "linear"]
# Property status bits of addProperty: 1 read-only, 4 hidden, 8 output (never touches the
# feature, so writing the report during a recompute does not mark it for another one).
READ_ONLY_OUTPUT = 1 | 8
HIDDEN_OUTPUT = 1 | 4 | 8

_PROPERTIES = [
    # type, name, group, doc, status
    ("App::PropertyLinkList", "Sources", GROUP,
     "Sketches, wires, edges, B-spline curves or point objects; each curve or point row is "
     "a row of the fit, in this order", 0),
    ("App::PropertyLinkSubList", "SourceEdges", GROUP,
     "Edges picked on other objects (e.g. Edge3 of a solid): each edge a row, after the rows "
     "of Sources", 0),
    ("App::PropertyFile", "SourceFile", GROUP,
     "A .rows/.csv file read by sfit's own reader; its rows come after those of Sources", 0),
    ("App::PropertyEnumeration", "ToleranceMode", GROUP,
     "Relative: T is ToleranceRelative times the data's bounding-box diagonal; Absolute: T "
     "is Tolerance", 0),
    ("App::PropertyLength", "Tolerance", GROUP,
     "Absolute tolerance T, per axis: every data point within T on x, y and z", 0),
    ("App::PropertyFloat", "ToleranceRelative", GROUP,
     "T as a fraction (0 ... 1) of the bounding-box diagonal of the data", 0),
    ("App::PropertyIntegerConstraint", "Degree", GROUP,
     "Degree of the surface in u (along a row) and v (across the rows), 1 ... 20", 0),
    ("App::PropertyEnumeration", "Closed", GROUP,
     "Closed directions: Auto (u when every row is a closed contour, v when the last row "
     "repeats the first), None, U, V, UV", 0),
    ("App::PropertyEnumeration", "Method", GROUP,
     "surface: the fewest control points over all points at once (sfit's default); sfit01: "
     "the paper's two stages", 0),
    ("App::PropertyEnumeration", "Parameters", GROUP,
     "How data points get parameters: auto (sfit's default) or one rule", 0),
    ("App::PropertyEnumeration", "Search", GROUP,
     "Control point count search: fast (default) or linear (the paper's)", 0),
    ("App::PropertyInteger", "SegmentsPerEdge", GROUP,
     "Samples of each edge: 0 = from the tolerance (chord sag within T, docs/freecad.md), "
     "else this many equal arc-length segments per edge", 0),
    # The report: read-only outputs of the last fit.
    ("App::PropertyString", "ControlPoints", REPORT,
     "Distinct control points nu x nv of the fitted surface", READ_ONLY_OUTPUT),
    ("App::PropertyVector", "ToleranceUsed", REPORT,
     "The per-axis tolerance (Tx, Ty, Tz) the fit held", READ_ONLY_OUTPUT),
    ("App::PropertyVector", "MaxDeviation", REPORT,
     "Largest deviation per axis over every data point (surface minus data)", READ_ONLY_OUTPUT),
    ("App::PropertyBool", "WithinTolerance", REPORT,
     "Every data point within T on every axis", READ_ONLY_OUTPUT),
    ("App::PropertyVector", "WorstPoint", REPORT,
     "The data point that uses most of its tolerance", READ_ONLY_OUTPUT),
    ("App::PropertyVector", "WorstDeviation", REPORT,
     "Its signed deviation, surface minus data", READ_ONLY_OUTPUT),
    ("App::PropertyString", "WorstPlace", REPORT,
     "Its row and index (from 0)", READ_ONLY_OUTPUT),
    ("App::PropertyString", "ClosedUsed", REPORT,
     "The closed directions the fit used (after Auto)", READ_ONLY_OUTPUT),
    ("App::PropertyInteger", "DataPoints", REPORT,
     "Number of data points fitted", READ_ONLY_OUTPUT),
    ("App::PropertyInteger", "Rows", REPORT, "Number of rows fitted", READ_ONLY_OUTPUT),
    # The data, for the deviation display.
    ("App::PropertyVectorList", "DataPointList", DATA, "Every fitted data point, row after row",
     HIDDEN_OUTPUT),
    ("App::PropertyIntegerList", "RowSizes", DATA, "The number of points of each row",
     HIDDEN_OUTPUT),
    ("App::PropertyFloatList", "DeviationRatio", DATA,
     "Each point's largest |d_k| / T_k over the axes (1 = at the tolerance)", HIDDEN_OUTPUT),
]


def fit_keywords(sfit):
    """The keywords this sfit module's fit() accepts (listed in its docstring)."""
    doc = sfit.fit.__doc__ or ""
    return {line.split(":")[0].strip() for line in doc.splitlines()
            if line.startswith("    ") and ":" in line}


class SurfaceFit:
    """Proxy of the feature: adds the properties, refits in execute()."""

    def __init__(self, obj):
        obj.Proxy = self
        self.ensure_properties(obj)

    @staticmethod
    def ensure_properties(obj):
        for typ, name, group, doc, status in _PROPERTIES:
            if name not in obj.PropertiesList:
                obj.addProperty(typ, name, group, doc, status)
        obj.ToleranceMode = TOLERANCE_MODES
        obj.Closed = CLOSED_CHOICES
        obj.Method = METHODS
        obj.Parameters = PARAMETERS
        obj.Search = SEARCHES
        obj.ToleranceRelative = 1e-3
        obj.Tolerance = 0.1
        obj.Degree = (3, 1, 20, 1)

    def onDocumentRestored(self, obj):
        obj.Proxy = self
        for typ, name, group, doc, status in _PROPERTIES:  # added by a later version
            if name not in obj.PropertiesList:
                obj.addProperty(typ, name, group, doc, status)

    def __getstate__(self):
        return None

    def __setstate__(self, state):
        return None

    def execute(self, obj):
        result = fit_feature(obj)
        obj.Shape = result["face"]


def create(doc, sources=(), source_file="", name="SurfaceFit", edges=(), **settings):
    """A new SurfaceFit feature in doc with these sources; edges: (object, "EdgeN") pairs;
    settings are property values."""
    obj = doc.addObject("Part::FeaturePython", name)
    SurfaceFit(obj)
    obj.Sources = list(sources)
    obj.SourceEdges = [(o, [sub]) for o, sub in edges]
    obj.SourceFile = source_file
    for key, value in settings.items():
        setattr(obj, key, value)
    return obj


def collect_rows(obj, sfit):
    """The rows of the feature's sources and the closed flags of each: (rows, closed, T)."""
    sources = list(obj.Sources)
    degree = obj.Degree
    if obj.ToleranceMode == "Absolute":
        t_sample = float(obj.Tolerance.Value)
    else:
        box = rows_mod.bounding_box(sources)
        for linked, subs in obj.SourceEdges:
            for sub in subs:
                sh = linked.getSubObject(sub)
                if sh is not None and hasattr(sh, "BoundBox"):
                    box.add(sh.BoundBox)
        diag = box.DiagonalLength if box.isValid() else 0.0
        t_sample = float(obj.ToleranceRelative) * diag
    rows, closed = [], []
    for src in sources:
        r, c = rows_mod.rows_of_object(src, t_sample, degree, int(obj.SegmentsPerEdge))
        rows += r
        closed += c
    for linked, subs in obj.SourceEdges:
        for sub in subs:
            edge = linked.getSubObject(sub)  # placed as in the document
            if edge is None or edge.ShapeType != "Edge":
                raise rows_mod.SourceError(f"{linked.Label}.{sub}: not an edge")
            row, c = rows_mod.sample_edges([edge], t_sample, degree, edge.isClosed(),
                                           int(obj.SegmentsPerEdge))
            rows.append(row)
            closed.append(c)
    if obj.SourceFile:
        if not os.path.isfile(obj.SourceFile):
            raise rows_mod.SourceError(f"SourceFile: {obj.SourceFile}: no such file")
        file_rows = rows_mod.rows_of_file(sfit, obj.SourceFile)
        rows += file_rows
        closed += [None] * len(file_rows)  # sfit's reader does not say; see closed_directions
    if not rows:
        raise rows_mod.SourceError("no rows: give Sources or a SourceFile")
    return rows, closed


def closed_directions(obj, rows, closed):
    """The closed argument for sfit.fit, and the rows (the repeated first row dropped for v)."""
    choice = obj.Closed
    if choice != "Auto":
        return ("" if choice == "None" else choice.lower()), rows
    all_pts = np.vstack(rows)
    size = float(np.linalg.norm(all_pts.max(axis=0) - all_pts.min(axis=0)))
    u = all(c for c in closed if c is not None) and any(c is not None for c in closed)
    if not any(c is not None for c in closed):  # only file rows: closed where every row's ends meet
        u = all(len(r) > 2 and np.all(np.abs(r[0] - r[-1]) <= 1e-9 * size) for r in rows)
        if u:
            rows = [r[:-1] for r in rows]
    v = len(rows) > 3 and rows_mod.same_row(rows[0], rows[-1], size)
    if v:
        rows = rows[:-1]
    return ("u" if u else "") + ("v" if v else ""), rows


def fit_options(obj, sfit):
    """The keywords of sfit.fit() for the feature's settings (those sfit's defaults leave out)."""
    known = fit_keywords(sfit)
    opts = {"degree": int(obj.Degree)}
    if obj.ToleranceMode == "Absolute":
        opts["tol"] = float(obj.Tolerance.Value)
    else:
        opts["tol_rel"] = float(obj.ToleranceRelative)
    if obj.Parameters != "auto":
        opts["parameters"] = obj.Parameters
    if obj.Search != "fast":
        opts["search"] = obj.Search
    if obj.Method != "surface":
        if "method" not in known:
            raise rows_mod.SourceError(
                f"Method {obj.Method}: this sfit Python module has no 'method' option "
                "(it fits by sfit's default method, surface)")
        opts["method"] = obj.Method
    return opts


def fit_feature(obj):
    """Fits the feature's rows; writes the report properties; returns the face and the fit."""
    sfit = find_sfit()
    rows, closed = collect_rows(obj, sfit)
    closed_arg, rows = closed_directions(obj, rows, closed)
    opts = fit_options(obj, sfit)
    result = sfit.fit(rows, closed=closed_arg, **opts)
    face = face_of(result.surface)
    write_report(obj, result, closed_arg)
    return {"face": face, "fit": result, "rows": rows, "closed": closed_arg, "options": opts}


def _knots_and_mults(full, degree, periodic, count_full):
    """OpenCASCADE's distinct knots and multiplicities of a full knot vector."""
    full = [float(k) for k in full]
    if periodic:  # the knots of the domain [knots[p], knots[n]], each once or as often as given
        full = full[degree:count_full + 1]
    knots, mults = [], []
    for k in full:
        if knots and k == knots[-1]:
            mults[-1] += 1
        else:
            knots.append(k)
            mults.append(1)
    return knots, mults


def surface_of(s):
    """Part.BSplineSurface from a sfit Surface: its knots and poles (distinct poles along a
    periodic direction: the stored form repeats the first `degree` of them)."""
    cp = np.asarray(s.control_points, dtype=float)
    pu, pv = int(s.degree_u), int(s.degree_v)
    per_u, per_v = (bool(x) for x in s.periodic)
    nu_full, nv_full = cp.shape[0], cp.shape[1]
    nu = nu_full - (pu if per_u else 0)
    nv = nv_full - (pv if per_v else 0)
    ku, mu = _knots_and_mults(s.knots_u, pu, per_u, nu_full)
    kv, mv = _knots_and_mults(s.knots_v, pv, per_v, nv_full)
    poles = [[FreeCAD.Vector(*cp[i, j]) for j in range(nv)] for i in range(nu)]
    surf = Part.BSplineSurface()
    surf.buildFromPolesMultsKnots(poles, mu, mv, ku, kv, per_u, per_v, pu, pv)
    return surf


def face_of(s):
    """The Part face on the whole surface."""
    return Part.Face(surface_of(s))


def write_report(obj, result, closed_arg):
    rep = result.report
    s = result.surface
    tol = [float(x) for x in rep["tolerance"]]
    obj.ControlPoints = f"{s.count[0]} x {s.count[1]}"
    obj.ToleranceUsed = FreeCAD.Vector(*tol)
    obj.MaxDeviation = FreeCAD.Vector(*[float(x) for x in rep["max_deviation"]])
    obj.WithinTolerance = bool(rep["within_tolerance"])
    pts = np.asarray(result.points, dtype=float)
    sizes = [int(n) for n in result.row_sizes]
    worst = rep["worst"]
    offsets = np.concatenate([[0], np.cumsum(sizes)])
    k = int(offsets[int(worst["row"])]) + int(worst["index"])
    obj.WorstPoint = FreeCAD.Vector(*pts[k])
    obj.WorstDeviation = FreeCAD.Vector(*[float(x) for x in worst["deviation"]])
    obj.WorstPlace = f"row {worst['row']}, point {worst['index']}"
    obj.ClosedUsed = closed_arg or "none"
    obj.DataPoints = len(pts)
    obj.Rows = len(sizes)
    # Each point's v: its own where the rule gives one (parameters geometric), else its row's.
    v_points = np.asarray(result.v_points)
    v = v_points if v_points.size else np.repeat(np.asarray(result.v), sizes)
    dev = s(np.asarray(result.u), v) - pts
    t = np.where(np.asarray(tol) > 0, np.asarray(tol), np.inf)
    ratio = np.max(np.abs(dev) / t, axis=1)
    obj.DataPointList = [FreeCAD.Vector(*p) for p in pts]
    obj.RowSizes = sizes
    obj.DeviationRatio = [float(x) for x in ratio]
