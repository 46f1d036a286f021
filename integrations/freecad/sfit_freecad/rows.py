"""Rows of points from FreeCAD objects (headless: FreeCAD and Part only, no GUI).

Each source gives one or more rows, in the order of the sources:
  * a point object (Points::Feature, its placement applied): one row, its points in order;
  * an object with a shape (sketch, wire, Part feature, B-spline curve, Draft object):
    each wire of its shape is a row; edges that belong to no wire are chained where their
    ends meet (Part.sortEdges) and each chain is a row; a shape of vertices only is one row
    of its vertices;
  * a .rows/.csv (or .srows, .step/.iges sections) file: the rows sfit's own reader gives.

Sampling rule (curves): one spacing h for the whole row, each edge sampled at equal arc
length with ceil(L_edge / h) segments, its end points included (so the corners of a wire are
data points and the samples are evenly spaced along the row). h keeps the chord sag between
neighbouring samples within the tolerance on every edge: h = min over the edges of
sqrt(8 T / k), k the edge's largest curvature found at 33 parameters, T the tolerance; and
h <= the row's length / (4 (degree + 1)), so a row has at least that many segments. An edge
gets at most 2000 segments. A closed row (its wire closed, or its ends within
1e-9 of the size) is given without repeating its first point, and fitted closed in u.
"""
import math

import numpy as np

import FreeCAD
import Part

MAX_SEGMENTS_PER_EDGE = 2000
CURVATURE_PROBES = 33


class SourceError(ValueError):
    """A source that gives no rows, named."""


def _is_points_object(obj):
    return obj.TypeId.startswith("Points::")


def bounding_box(objects):
    """The union of the sources' bounding boxes (their placements applied)."""
    box = FreeCAD.BoundBox()
    for obj in objects:
        if _is_points_object(obj):
            for p in _points_of(obj):
                box.add(FreeCAD.Vector(*p))
        elif hasattr(obj, "Shape") and not obj.Shape.isNull():
            box.add(obj.Shape.BoundBox)
    return box


def _points_of(obj):
    pl = obj.Placement
    return np.array([tuple(pl.multVec(p)) for p in obj.Points.Points], dtype=float)


def _max_curvature(edge):
    a, b = edge.ParameterRange
    k = 0.0
    for i in range(CURVATURE_PROBES):
        t = a + (b - a) * i / (CURVATURE_PROBES - 1)
        try:
            k = max(k, abs(edge.curvatureAt(t)))
        except Exception:  # a degenerate point of the curve: no curvature there
            pass
    return k


def edge_spacing(edge, tol):
    """The largest arc-length spacing whose chord sag on this edge stays within tol:
    sqrt(8 tol / k), k the edge's largest curvature; infinite on a straight edge."""
    k = _max_curvature(edge)
    if k <= 0:
        return math.inf
    return math.sqrt(8.0 * max(tol, 0.0) / k)


def row_segments(edges, tol, degree):
    """Segments per edge under the sampling rule: one spacing for the whole row (the
    smallest of its edges', and at most the row's length over 4 (degree + 1)), so the
    samples are evenly spaced along the row, corners included."""
    lengths = [e.Length for e in edges]
    total = sum(lengths)
    if total <= 0:
        return [0] * len(edges)
    h = min([edge_spacing(e, tol) for e in edges] + [total / (4 * (degree + 1))])
    return [0 if L <= 0 else int(min(max(math.ceil(L / h - 1e-9), 1), MAX_SEGMENTS_PER_EDGE))
            for L in lengths]


def _chain(edges, counts):
    """Samples a chain of edges into one polyline, each edge turned to follow the last."""
    sampled = []
    for e, n in zip(edges, counts):
        if n <= 0:
            continue
        q = np.array([tuple(v) for v in e.discretize(Number=n + 1)], dtype=float)
        sampled.append(q)
    if not sampled:
        return np.zeros((0, 3))
    if len(sampled) > 1:  # the first edge runs towards the second
        s, t = sampled[0], sampled[1]
        if min(np.linalg.norm(s[0] - t[0]), np.linalg.norm(s[0] - t[-1])) < \
                min(np.linalg.norm(s[-1] - t[0]), np.linalg.norm(s[-1] - t[-1])):
            sampled[0] = s[::-1]
    pts = [sampled[0]]
    for q in sampled[1:]:
        end = pts[-1][-1]
        if np.linalg.norm(q[-1] - end) < np.linalg.norm(q[0] - end):
            q = q[::-1]
        pts.append(q[1:])
    return np.vstack(pts)


def sample_edges(edges, tol, degree, closed_hint=False, fixed_segments=0):
    """One row from a chain of edges: (points (N, 3), closed)."""
    if fixed_segments > 0:
        counts = [fixed_segments if e.Length > 0 else 0 for e in edges]
    else:
        counts = row_segments(edges, tol, degree)
    size = max(sum(e.Length for e in edges), 1e-300)
    row = _chain(edges, counts)
    closed = closed_hint or (len(row) > 2 and np.linalg.norm(row[0] - row[-1]) <= 1e-9 * size)
    if closed:
        row = row[:-1]
    return row, closed


def rows_of_shape(shape, tol, degree, fixed_segments=0):
    """Rows of one shape: (list of (N, 3) arrays, list of closed flags)."""
    rows, closed = [], []
    in_wires = set()
    for w in shape.Wires:
        edges = w.OrderedEdges if len(w.Edges) > 1 else w.Edges
        row, c = sample_edges(edges, tol, degree, w.isClosed(), fixed_segments)
        rows.append(row)
        closed.append(c)
        for e in w.Edges:
            in_wires.add(e.hashCode())
    loose = [e for e in shape.Edges if e.hashCode() not in in_wires]
    if loose:
        for group in Part.sortEdges(loose):
            row, c = sample_edges(group, tol, degree, False, fixed_segments)
            rows.append(row)
            closed.append(c)
    if not rows and shape.Vertexes:
        rows.append(np.array([tuple(v.Point) for v in shape.Vertexes], dtype=float))
        closed.append(False)
    return rows, closed


def rows_of_object(obj, tol, degree, fixed_segments=0):
    """Rows of one document object: (rows, closed flags)."""
    if _is_points_object(obj):
        return [_points_of(obj)], [False]
    shape = getattr(obj, "Shape", None)
    if shape is None or shape.isNull():
        raise SourceError(f"{obj.Label}: no shape and no points to take rows from")
    rows, closed = rows_of_shape(shape, tol, degree, fixed_segments)
    if not rows:
        raise SourceError(f"{obj.Label}: its shape has no wires, edges or vertices")
    return rows, closed


def rows_of_file(sfit, path):
    """Rows of a .rows/.csv/... file through sfit's own reader."""
    return [np.asarray(r, dtype=float) for r in sfit.load_rows(path)]


def same_row(a, b, size):
    """True when two rows are the same points (a closed sequence's first row repeated)."""
    return a.shape == b.shape and np.all(np.abs(a - b) <= 1e-9 * max(size, 1e-300))
