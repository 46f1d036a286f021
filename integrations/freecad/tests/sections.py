"""Sections as FreeCAD users draw them, shared by the workbench's tests (freecadcmd) and its
screenshot (the GUI): closed rings and open wing sections in sketches, rows of point objects."""
import math

import FreeCAD as App
import Part
import Sketcher

V = App.Vector


def sketch(doc, name, placement):
    sk = doc.addObject("Sketcher::SketchObject", name)
    sk.Placement = placement
    return sk


def closed_sections(doc):
    """Five closed sections up z: circles whose radius is a constraint, and one rounded
    rectangle (a wire of four lines and four arcs)."""
    secs = []
    for i, (r, cx) in enumerate([(10, 0), (12, 1), (13, 2), (12, 2), (9, 1)]):
        sk = sketch(doc, f"Ring{i}", App.Placement(V(0, 0, 10 * i), App.Rotation()))
        if i == 2:  # a rounded rectangle, its corners arcs of radius 3
            w, h, c = 13, 9, 3
            pts = [(-w + c, -h), (w - c, -h), (w, -h + c), (w, h - c), (w - c, h), (-w + c, h),
                   (-w, h - c), (-w, -h + c)]
            for a, b in ((0, 1), (2, 3), (4, 5), (6, 7)):
                sk.addGeometry(Part.LineSegment(V(pts[a][0] + cx, pts[a][1], 0),
                                                V(pts[b][0] + cx, pts[b][1], 0)))
            for (x, y), a0 in (((w - c, -h + c), -90), ((w - c, h - c), 0), ((-w + c, h - c), 90),
                               ((-w + c, -h + c), 180)):
                sk.addGeometry(Part.ArcOfCircle(Part.Circle(V(x + cx, y, 0), V(0, 0, 1), c),
                                                math.radians(a0), math.radians(a0 + 90)))
        else:
            sk.addGeometry(Part.Circle(V(cx, 0, 0), V(0, 0, 1), r))
            sk.addConstraint(Sketcher.Constraint("Radius", 0, r))
        secs.append(sk)
    return secs


def open_sections(doc):
    """Four open sections along y, each an interpolated B-spline and a line (a wire of two
    edges), in planes x-z turned about x."""
    secs = []
    for i in range(4):
        sk = sketch(doc, f"Wing{i}", App.Placement(V(0, 15 * i, 0), App.Rotation(V(1, 0, 0), 90)))
        bs = Part.BSplineCurve()
        amp = 4 + i
        bs.interpolate([V(x, amp * math.sin(math.pi * x / 40) + 0.5 * i, 0)
                        for x in (0, 8, 16, 24, 32, 40)])
        sk.addGeometry(bs)
        end = bs.value(bs.LastParameter)
        sk.addGeometry(Part.LineSegment(V(end.x, end.y, 0), V(end.x + 10, end.y - 2, 0)))
        secs.append(sk)
    return secs


def point_rows(doc):
    import Points
    objs = []
    for i in range(5):
        pk = Points.Points()
        pk.addPoints([V(x, 8 * i, 3 * math.cos(x / 9.0) + 0.2 * i * i) for x in range(0, 50, 2)])
        o = doc.addObject("Points::Feature", f"Scan{i}")
        o.Points = pk
        objs.append(o)
    return objs


def torus_sections(doc, n=8):
    """n circles of radius 3 around the z axis at distance 10 (the sections of a torus),
    each in its own sketch."""
    secs = []
    for i in range(n):
        a = 360.0 * i / n
        rot = App.Rotation(V(0, 0, 1), a).multiply(App.Rotation(V(1, 0, 0), 90))
        sk = sketch(doc, f"Tube{i}", App.Placement(V(10 * math.cos(math.radians(a)),
                                                     10 * math.sin(math.radians(a)), 0), rot))
        sk.addGeometry(Part.Circle(V(0, 0, 0), V(0, 0, 1), 3 + 0.3 * (i % 2)))
        secs.append(sk)
    return secs
