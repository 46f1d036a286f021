"""Rows of points from FreeCAD objects (headless: FreeCAD and Part only, no GUI).

Each source gives one or more rows, in the order of the sources:
  * a point object (Points::Feature, its placement applied): one row, its points in order;
  * an object with a shape (sketch, wire, Part feature, B-spline curve, Draft object):
    each wire of its shape is a row; edges that belong to no wire are chained where their
    ends meet (Part.sortEdges) and each chain is a row; a shape of vertices only is one row
    of its vertices;
  * a .rows/.csv (or .srows, .step/.iges sections) file: the rows sfit's own reader gives.

Sampling rule (curves): each edge of a row is sampled at equal arc length, its end points
included (so the corners of a wire are data points). The spacing h keeps the chord sag
between neighbouring samples within the tolerance: h = sqrt(8 T / k), k the largest
curvature found at 33 parameters on the edge, T the smallest of the per-axis tolerances;
a straight edge gets one segment. A row gets at least 4 (degree + 1) points (spacing made
finer evenly), an edge at most 2000 segments. A closed row (its wire closed, or its ends within
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


def edge_segments(edge, tol):
    """The number of equal-arc-length segments of an edge under the sampling rule."""
    if edge.Length <= 0:
        return 0
    k = _max_curvature(edge)
    if k <= 0 or tol <= 0:
        n = 1 if k <= 0 else MAX_SEGMENTS_PER_EDGE
    else:
        n = math.ceil(edge.Length / math.sqrt(8.0 * tol / k))
    return int(min(max(n, 1), MAX_SEGMENTS_PER_EDGE))


def _chain(edges, counts):
    """Samples a chain of edges into one polyline, each edge turned to follow the last."""
    pts = []
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
        counts = [edge_segments(e, tol) for e in edges]
    total_length = sum(e.Length for e in edges)
    size = max(total_length, 1e-300)
    row = _chain(edges, counts)
    closed = closed_hint or (len(row) > 2 and np.linalg.norm(row[0] - row[-1]) <= 1e-9 * size)
    minimum = 4 * (degree + 1)
    if fixed_segments <= 0 and len(row) - (1 if closed else 0) < minimum and total_length > 0:
        # finer evenly: each edge's share of the minimum by its length
        counts = [max(c, math.ceil(minimum * e.Length / total_length)) if e.Length > 0 else 0
                  for e, c in zip(edges, counts)]
        row = _chain(edges, counts)
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
