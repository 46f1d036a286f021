"""sfit's mesh and VTK files read by VTK (Debian python3-vtk9), as ParaView reads them.

For every case (bundled examples, a torus, a tube, a height field, and the torus at the
ends of the accepted size range and a far offset) the CLI writes .vtk .vts .stl .ply .obj
and this checks, from what VTK read:
- counts: points, triangles/quads, data points, structured extents;
- points: equal to sfit's own evaluation (surface_probe) on the same grid, bounds included;
- arrays: normals (unit), curvature, its clipped copy and range, deviation (vts and vtk),
  no NaN at any (regular) point;
- topology: no boundary edge where the surface is closed, none non-manifold;
- orientation: closed surfaces outward (positive signed volume, the open ends capped),
  height fields up (+z), triangles wound with the normals, --normals flip reverses both;
- scale: the torus at 1e+-100 and 1e+-149 has the normals of the unit torus and its
  curvature scaled by 1/size; STL (float32) is refused where coordinates do not fit;
- .obj is a triangle mesh by default, and the default density keeps a triangle budget.
Skips (exit 77) with a message when VTK is not importable.
"""
import json
import math
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import viewer_cases as vc  # noqa: E402

try:
    import numpy as np
    from scipy.spatial import cKDTree
    from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
    from vtkmodules.vtkCommonCore import vtkPoints
    from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData
    from vtkmodules.vtkFiltersCore import vtkCleanPolyData, vtkFeatureEdges
    from vtkmodules.vtkIOGeometry import vtkOBJReader, vtkSTLReader
    from vtkmodules.vtkIOLegacy import vtkPolyDataReader
    from vtkmodules.vtkIOPLY import vtkPLYReader
    from vtkmodules.vtkIOXML import vtkXMLStructuredGridReader
except ImportError as e:
    print(f"SKIPPED: VTK for Python is not available to {sys.executable} ({e}); "
          "install python3-vtk9 (scripts/deps/viewers.txt)")
    sys.exit(vc.SKIP)

N = 24  # --mesh-density of the counted meshes
C = vc.Checks("vtk_files_test")


def read(path):
    ext = os.path.splitext(path)[1]
    reader = {".vtk": vtkPolyDataReader, ".vts": vtkXMLStructuredGridReader, ".stl": vtkSTLReader,
              ".ply": vtkPLYReader, ".obj": vtkOBJReader}[ext]()
    reader.SetFileName(path)
    if ext == ".vtk":  # every array, as ParaView reads them
        reader.ReadAllScalarsOn()
        reader.ReadAllVectorsOn()
        reader.ReadAllNormalsOn()
        reader.ReadAllFieldsOn()
    reader.Update()
    return reader.GetOutput()


def points_of(data):
    return vtk_to_numpy(data.GetPoints().GetData()).astype(float) if data.GetPoints() else \
        np.zeros((0, 3))


def polys_of(poly):
    """Cells of a vtkPolyData's polygons as a list of index tuples."""
    cells, out = poly.GetPolys(), []
    conn = vtk_to_numpy(cells.GetConnectivityArray())
    offs = vtk_to_numpy(cells.GetOffsetsArray())
    for k in range(len(offs) - 1):
        out.append(tuple(conn[offs[k]:offs[k + 1]]))
    return out


def structured_quads(grid):
    """The cells of a 2D vtkStructuredGrid, as VTK defines them: (i,j) (i+1,j) (i+1,j+1) (i,j+1)."""
    nx, ny, _ = grid.GetDimensions()
    return [(i + j * nx, i + 1 + j * nx, i + 1 + (j + 1) * nx, i + (j + 1) * nx)
            for j in range(ny - 1) for i in range(nx - 1)]


def edge_counts(poly):
    """(boundary, non-manifold) edges after joining identical points, found by VTK on a copy
    with the points centred and scaled to 1 in double precision (VTK's filters would round
    far offsets and extreme sizes to float32)."""
    pts = points_of(poly)
    faces = polys_of(poly)
    scaled = (pts - pts.mean(axis=0)) / max(np.abs(pts - pts.mean(axis=0)).max(), 1e-300)
    vp = vtkPoints()
    vp.SetDataTypeToDouble()
    vp.SetData(numpy_to_vtk(scaled, deep=True))
    cells = vtkCellArray()
    for f in faces:
        cells.InsertNextCell(len(f), [int(k) for k in f])
    copy = vtkPolyData()
    copy.SetPoints(vp)
    copy.SetPolys(cells)
    clean = vtkCleanPolyData()
    clean.SetOutputPointsPrecision(1)  # double
    clean.SetInputData(copy)
    clean.SetTolerance(0.0)
    clean.Update()
    counts = []
    for boundary in (True, False):
        f = vtkFeatureEdges()
        f.SetInputData(clean.GetOutput())
        f.SetBoundaryEdges(boundary)
        f.SetNonManifoldEdges(not boundary)
        f.SetFeatureEdges(False)
        f.SetManifoldEdges(False)
        f.Update()
        counts.append(f.GetOutput().GetNumberOfCells())
    return counts


def signed_volume(points, faces):
    """Volume enclosed by the faces (fans of polygons), the open ends capped with a fan to
    their centroid: positive when the faces wind counter-clockwise seen from outside."""
    p = points - points.mean(axis=0)
    p = p / np.abs(p).max()  # scale-free
    vol = 0.0
    directed = {}
    for f in faces:
        for k in range(1, len(f) - 1):
            vol += np.dot(p[f[0]], np.cross(p[f[k]], p[f[k + 1]]))
        for k in range(len(f)):
            a, b = f[k], f[(k + 1) % len(f)]
            directed[(a, b)] = directed.get((a, b), 0) + 1
    boundary = [(a, b) for (a, b) in directed if (b, a) not in directed]
    parent = {}

    def root(x):
        while parent.setdefault(x, x) != x:
            x = parent[x]
        return x

    for a, b in boundary:
        parent[root(a)] = root(b)
    loops = {}
    for a, b in boundary:
        loops.setdefault(root(a), []).append((a, b))
    for edges in loops.values():
        centre = np.mean([p[a] for a, _ in edges], axis=0)
        for a, b in edges:  # the cap closes the edge a -> b with b -> a
            vol += np.dot(centre, np.cross(p[b], p[a]))
    return vol / 6


def face_normal(points, f):
    n = np.zeros(3)
    for k in range(1, len(f) - 1):
        n += np.cross(points[f[k]] - points[f[0]], points[f[k + 1]] - points[f[0]])
    return n


def winding_agreement(points, faces, normals):
    """Fraction of faces whose winding agrees with the mean of their vertex normals."""
    p = points / np.abs(points).max()
    good = sum(1 for f in faces if np.dot(face_normal(p, f), normals[list(f)].sum(axis=0)) > 0)
    return good / max(1, len(faces))


def rows_point_count(path):
    n = 0
    with open(path) as f:
        for line in f:
            s = line.split("#")[0].strip()
            if s:
                n += 1
    return n


def close_sets(a, b, rel):
    """Every point of a is one of b's and back, within rel of the largest coordinate."""
    if a.shape != b.shape or not len(a):
        return False
    scale = max(np.abs(b).max(), 1e-300)
    a, b = a / scale, b / scale
    return max(cKDTree(b).query(a)[0].max(), cKDTree(a).query(b)[0].max()) <= rel


def check_case(ws, case, extreme):
    # VTK reads PLY and OBJ points as float32 and STL holds float32: the extreme cases are
    # read through the double-precision .vtk and .vts only.
    exts = ["vtk", "vts"] + ([] if extreme else ["ply", "obj", "stl"])
    ws.fit(case, exts, ["--fields", "--mesh-density", str(N)])
    probe = ws.probe(case, N)
    pu, pv = probe["periodic"]
    grid = np.array([g[2:] for g in probe["grid"]])
    extent = np.abs(grid - grid.mean(axis=0)).max()
    lo, hi = grid.min(axis=0), grid.max(axis=0)
    qu, qv = (N if pu else N - 1), (N if pv else N - 1)
    triangles = 2 * qu * qv
    name = case.name
    want_boundary = (0 if pu else 2 * qv) + (0 if pv else 2 * qu)
    height_field = name.startswith("bump")
    closed = pu or pv

    def orientation(tag, pts, faces, normals):
        if closed:
            C.check(signed_volume(pts, faces) > 0,
                    f"{name}.{tag}: closed surface, normals outward (signed volume > 0)")
        if height_field:
            C.check(normals is None or normals[:, 2].min() > 0,
                    f"{name}.{tag}: height field, normals up (+z)")
            fz = [face_normal(pts / extent, f)[2] for f in faces]
            C.check(min(fz) > 0, f"{name}.{tag}: height field, triangles wound counter-clockwise"
                                 " seen from above")
        if normals is not None:
            agree = winding_agreement(pts, faces, normals)
            C.check(agree >= 0.95, f"{name}.{tag}: triangles wound with the normals "
                                    f"({agree:.4f} agree)")

    # Triangle meshes (VTK reads their points as float32: compared at float precision).
    for ext in [] if extreme else ["ply", "obj", "stl"]:
        path = ws.path(f"{name}.{ext}")
        mesh = read(path)
        pts = points_of(mesh)
        faces = polys_of(mesh)
        C.check(len(faces) == triangles,
                f"{name}.{ext}: {triangles} triangles, VTK read {len(faces)} (free-form OBJ reads "
                "as none)" if ext == "obj" else f"{name}.{ext}: {triangles} triangles, VTK read "
                f"{len(faces)}")
        C.check(all(len(f) == 3 for f in faces), f"{name}.{ext}: every face a triangle")
        C.check(mesh.GetNumberOfPoints() == N * N,
                f"{name}.{ext}: {N * N} points, VTK read {mesh.GetNumberOfPoints()}")
        if not faces:
            continue
        rel = 1e-6  # VTK's readers of these three hold float32 points
        C.check(close_sets(pts, grid, rel), f"{name}.{ext}: points equal sfit's evaluation")
        b = np.array(mesh.GetBounds()).reshape(3, 2)
        C.check(np.abs(b[:, 0] - lo).max() <= rel * np.abs(grid).max() * 4 and
                np.abs(b[:, 1] - hi).max() <= rel * np.abs(grid).max() * 4,
                f"{name}.{ext}: bounds {b.tolist()} are the surface's {lo.tolist()} {hi.tolist()}")
        boundary, nonmanifold = edge_counts(mesh)
        C.check(boundary == want_boundary,
                f"{name}.{ext}: {want_boundary} boundary edges (closed: {pu}, {pv}), VTK finds "
                f"{boundary}")
        C.check(nonmanifold == 0, f"{name}.{ext}: no non-manifold edge ({nonmanifold})")
        nrm = mesh.GetPointData().GetNormals()
        normals = vtk_to_numpy(nrm).astype(float) if nrm is not None else None
        if ext != "stl":
            C.check(normals is not None, f"{name}.{ext}: has vertex normals")
        orientation(ext, pts, faces, normals)

    # Legacy VTK: the grid as quads, the data points as vertices, the fields.
    vtk = read(ws.path(f"{name}.vtk"))
    nd = rows_point_count(case.rows_path)
    C.check(vtk.GetNumberOfPoints() == N * N + nd,
            f"{name}.vtk: {N * N} grid + {nd} data points, VTK read {vtk.GetNumberOfPoints()}")
    C.check(vtk.GetNumberOfVerts() == nd, f"{name}.vtk: {nd} data vertices")
    quads = polys_of(vtk)
    C.check(len(quads) == qu * qv and all(len(q) == 4 for q in quads),
            f"{name}.vtk: {qu * qv} quads, VTK read {len(quads)}")
    vpts = points_of(vtk)
    C.check(close_sets(vpts[:N * N], grid, 1e-14), f"{name}.vtk: grid points equal sfit's "
                                                    "evaluation")
    pd = vtk.GetPointData()
    arrays = {pd.GetArrayName(k): vtk_to_numpy(pd.GetArray(k)).astype(float)
              for k in range(pd.GetNumberOfArrays())}
    for a in ("normals", "mean_curvature", "gaussian_curvature", "mean_curvature_clipped",
              "gaussian_curvature_clipped", "deviation", "deviation_ratio"):
        C.check(a in arrays, f"{name}.vtk: point data '{a}' (has {sorted(arrays)})")
    for a, v in arrays.items():
        C.check(np.isfinite(v).all(), f"{name}.vtk: '{a}' finite at every point "
                                      f"({int((~np.isfinite(v)).sum())} not)")
    if "normals" in arrays:
        C.check(np.abs(np.linalg.norm(arrays["normals"], axis=1) - 1).max() < 1e-9,
                f"{name}.vtk: unit normals")
        boundary, _ = edge_counts(vtk)
        C.check(boundary == want_boundary, f"{name}.vtk: {want_boundary} boundary edges, VTK "
                                           f"finds {boundary}")
        orientation("vtk", vpts, quads, arrays["normals"])
    if "deviation_ratio" in arrays:
        r = arrays["deviation_ratio"]
        C.check(r.max() <= 1 + 1e-12, f"{name}.vtk: deviation within T everywhere "
                                      f"(max ratio {r.max():.6g})")
        with open(ws.path(name + ".json")) as f:
            rep = json.load(f)["report"]
        want = max(d / t if t > 0 else d for d, t in zip(rep["max_deviation"], rep["tolerance"]))
        got = r[N * N:].max()
        C.check(abs(got - want) <= 1e-5 * max(want, 1e-300) + 1e-12,  # far offsets round
                f"{name}.vtk: the data points' largest deviation ratio {got:.9g} is the fit "
                f"report's {want:.9g}")
    fd = vtk.GetFieldData()
    ranges = {fd.GetArrayName(k): vtk_to_numpy(fd.GetArray(k)).astype(float)
              for k in range(fd.GetNumberOfArrays())} if fd else {}
    for a in ("mean_curvature", "gaussian_curvature"):
        key = a + "_range"
        if C.check(key in ranges, f"{name}.vtk: field data '{key}' (has {sorted(ranges)})") and \
                a + "_clipped" in arrays:
            clip = arrays[a + "_clipped"][:N * N]
            lo_c, hi_c = ranges[key][0], ranges[key][1]
            C.check(clip.min() >= lo_c and clip.max() <= hi_c,
                    f"{name}.vtk: {a}_clipped within its range [{lo_c:.4g}, {hi_c:.4g}]")

    # VTK XML structured grid: the seam repeated, the same arrays, deviation on the grid.
    vts = read(ws.path(f"{name}.vts"))
    dims = vts.GetDimensions()
    C.check(tuple(dims) == (N + pu, N + pv, 1), f"{name}.vts: dimensions {dims}")
    spts = points_of(vts)
    C.check(close_sets(np.unique(spts, axis=0), np.unique(grid, axis=0), 1e-14),
            f"{name}.vts: points equal sfit's evaluation")
    pd = vts.GetPointData()
    sarr = {pd.GetArrayName(k): vtk_to_numpy(pd.GetArray(k)).astype(float)
            for k in range(pd.GetNumberOfArrays())}
    for a in ("normals", "mean_curvature", "gaussian_curvature", "mean_curvature_clipped",
              "gaussian_curvature_clipped", "deviation", "deviation_ratio"):
        C.check(a in sarr, f"{name}.vts: point data '{a}' (has {sorted(sarr)})")
    for a, v in sarr.items():
        C.check(np.isfinite(v).all(), f"{name}.vts: '{a}' finite at every point "
                                      f"({int((~np.isfinite(v)).sum())} not)")
    if "deviation_ratio" in sarr:
        C.check(sarr["deviation_ratio"].max() <= 1 + 1e-12,
                f"{name}.vts: deviation within T on the grid")
    if "normals" in sarr:
        squads = structured_quads(vts)
        orientation("vts", spts, squads, sarr["normals"])
        cells = vtkCellArray()
        for q in squads:
            cells.InsertNextCell(4, q)
        surf = vtkPolyData()
        surf.SetPoints(vts.GetPoints())
        surf.SetPolys(cells)
        boundary, _ = edge_counts(surf)
        C.check(boundary == want_boundary, f"{name}.vts: {want_boundary} boundary edges once the "
                                           f"repeated seam is joined, VTK finds {boundary}")
    return {"grid": grid, "vtk": arrays, "vts": sarr}


def check_scale_free(results):
    """The scaled tori are the unit torus: same normals, curvature times the size."""
    base = results.get("torus")
    for name, size in (("torus_1e149", 1e149), ("torus_1e-149", 1e-149), ("torus_1e100", 1e100),
                       ("torus_1e-100", 1e-100)):
        r = results.get(name)
        if base is None or r is None:
            continue
        C.check(np.abs(r["grid"] / size - base["grid"]).max() < 1e-9,
                f"{name}: the grid is the unit torus's times {size:g}")
        for fmt in ("vtk", "vts"):
            a, b = r[fmt], base[fmt]
            if "normals" in a and "normals" in b:
                C.check(np.abs(a["normals"] - b["normals"]).max() < 1e-9,
                        f"{name}.{fmt}: the normals of the unit torus")
            for k, power in (("mean_curvature", 1), ("gaussian_curvature", 2)):
                if k in a and k in b:
                    scaled = a[k][:N * N] * size ** power
                    ref = b[k][:N * N]
                    C.check(np.abs(scaled - ref).max() <= 1e-6 * np.abs(ref).max(),
                            f"{name}.{fmt}: {k} is the unit torus's / size^{power}")


def check_stl_limits(ws, cases):
    for case in cases:
        if case.name in ("torus_1e149", "torus_1e-149", "bump_offset_1e7"):
            out = ws.path(case.name + "_refused.stl")
            r = vc.run([ws.cli, "fit", case.rows_path, *case.closed_flag, "-o", out], check=False)
            C.check(r.returncode != 0 and "STL" in r.stderr and not os.path.exists(out),
                    f"{case.name}: STL (float32) refused with a message, nothing written "
                    f"(exit {r.returncode}: {r.stderr.strip()[-200:]})")


def check_defaults(ws, cases):
    """.obj is a triangle mesh unless asked otherwise; the default density keeps the
    triangle budget; stderr says what was written; --normals flip flips."""
    for case in cases:
        if case.name not in ("iea3p4mw_blade_ragged9", "torus", "bump"):
            continue
        err = ws.fit(case, ["obj", "stl"])
        obj = read(ws.path(case.name + ".obj"))
        tris = len(polys_of(obj))
        C.check(tris > 0, f"{case.name}: default .obj is a triangle mesh ({tris} triangles)")
        C.check(re.search(r"wrote .*\.obj \(triangle mesh", err) is not None,
                f"{case.name}: stderr says the .obj is a triangle mesh: {err.strip()[-300:]}")
        stl = read(ws.path(case.name + ".stl"))
        C.check(0 < stl.GetNumberOfCells() <= 100000,
                f"{case.name}: default mesh within the 100000-triangle budget "
                f"({stl.GetNumberOfCells()})")
        err = ws.fit(case, ["obj"], ["--obj-freeform"])
        with open(ws.path(case.name + ".obj")) as f:
            C.check("cstype bspline" in f.read(), f"{case.name}: --obj-freeform writes free-form")
        C.check("free-form" in err, f"{case.name}: stderr says the .obj is free-form")
        ws.fit(case, ["ply"], ["--mesh-density", str(N)])
        a = read(ws.path(case.name + ".ply"))
        ws.fit(case, ["ply"], ["--mesh-density", str(N), "--normals", "flip"])
        b = read(ws.path(case.name + ".ply"))
        na = vtk_to_numpy(a.GetPointData().GetNormals()).astype(float)
        nb = vtk_to_numpy(b.GetPointData().GetNormals()).astype(float)
        pa, pb = points_of(a), points_of(b)
        C.check(np.array_equal(pa, pb) and np.abs(na + nb).max() < 1e-6,
                f"{case.name}: --normals flip gives the opposite normals")
        fa, fb = polys_of(a), polys_of(b)
        C.check(winding_agreement(pb, fb, nb) >= 0.95 and
                signed_volume(pa, fa) * signed_volume(pb, fb) < 0,
                f"{case.name}: --normals flip reverses the winding with the normals")


def main():
    ws = vc.Workspace()
    cases = ws.cases(extremes=True)
    results = {}
    for case in cases:
        try:
            results[case.name] = check_case(ws, case, extreme=case.name not in (
                "ship_px121_stations", "d150_wing", "iea3p4mw_blade_ragged9", "torus", "tube",
                "bump"))
        except Exception as e:  # a failed run or an unreadable file is a failed check
            C.check(False, f"{case.name}: {type(e).__name__}: {e}")
    check_scale_free(results)
    check_stl_limits(ws, cases)
    try:
        check_defaults(ws, cases)
    except Exception as e:
        C.check(False, f"defaults: {type(e).__name__}: {e}")
    C.finish()


if __name__ == "__main__":
    main()
