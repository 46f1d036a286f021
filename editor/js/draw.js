// What the view shows: the surface (shaded, deviation, zebra, curvature), the data points and
// their rows, the control net (drawn over the surface, its points pickable), the markers and
// the drag's constraint (a plane patch or an axis line).
import * as THREE from "three";
import { $, S, hook } from "./store.js";
import { world, redraw, local } from "./view.js";
import { sampleCounts, Tessellator } from "./bspline.js";
import { curvatureColour, deviationColour } from "./colours.js";
import { showLegend } from "./legend.js";

let surfaceMesh = null, pointsObj = null, rowLines = null, netLines = null, netPoints = null;
let marker = null, selMarker = null, failMarks = null, tess = null;

// Zebra stripes: reflection lines, anti-aliased by the stripe function's screen-space
// derivative (fwidth), with a count and a direction (the axis the reflected ray is read along).
const zebraUniforms = { count: { value: 8 }, dir: { value: new THREE.Vector3(0, 1, 0) } };
const zebraMaterial = new THREE.ShaderMaterial({
  side: THREE.DoubleSide,
  uniforms: zebraUniforms,
  polygonOffset: true, polygonOffsetFactor: 2, polygonOffsetUnits: 4,
  vertexShader: `varying vec3 vN; varying vec3 vP;
    void main() { vN = normalize(normalMatrix * normal); vec4 p = modelViewMatrix * vec4(position, 1.0);
      vP = p.xyz; gl_Position = projectionMatrix * p; }`,
  fragmentShader: `uniform float count; uniform vec3 dir; varying vec3 vN; varying vec3 vP;
    void main() { vec3 r = reflect(normalize(vP), normalize(vN));
      float x = count * (dot(r, dir) * 0.5 + 0.5);
      float w = clamp(fwidth(x), 1e-4, 0.5);
      float d = abs(fract(x) - 0.5);
      float s = smoothstep(0.25 - w, 0.25 + w, d);
      gl_FragColor = vec4(vec3(0.08 + 0.85 * s), 1.0); }`,
});
export function setZebra(count, dir) {
  zebraUniforms.count.value = count;
  zebraUniforms.dir.value.set(...dir).normalize();
  redraw();
}
// Phong, not the physically based MeshStandardMaterial: far cheaper per pixel on software GL.
// The surface is pushed back in depth (polygon offset) so the control net and the row lines
// that lie on it are drawn over it, still hidden by the parts of the surface in front.
const offset = { polygonOffset: true, polygonOffsetFactor: 2, polygonOffsetUnits: 4 };
const shadedMaterial = new THREE.MeshPhongMaterial({
  color: 0x8fb3d9, side: THREE.DoubleSide, shininess: 40, specular: 0x333333, ...offset });
const colouredMaterial = new THREE.MeshPhongMaterial({
  vertexColors: true, side: THREE.DoubleSide, shininess: 20, specular: 0x222222, ...offset });

// Fraction of T used at (u, v) of the surface: from the nearest points of the two rows
// around v, blended along v.
function deviationAt(u, v) {
  const vs = S.params.v, dev = S.dev;
  let j = 0;
  while (j + 1 < vs.length && vs[j + 1] <= v) j++;
  const near = (r) => {
    const us = S.params.u[r];
    let lo = 0, hi = us.length - 1;
    while (hi - lo > 1) { const m = (lo + hi) >> 1; if (us[m] <= u) lo = m; else hi = m; }
    return Math.abs(us[lo] - u) <= Math.abs(us[hi] - u) ? dev[r][lo] : dev[r][hi];
  };
  if (j + 1 >= vs.length || vs[j + 1] === vs[j]) return near(j);
  const t = Math.max(0, Math.min(1, (v - vs[j]) / (vs[j + 1] - vs[j])));
  return (1 - t) * near(j) + t * near(j + 1);
}

let curvatureScale = 1;
function surfaceColours(mode) {
  const n = tess.su * tess.sv, c = new Float32Array(3 * n);
  if (mode === "deviation" && S.params && S.dev.length) {
    for (let i = 0; i < n; i++) deviationColour(deviationAt(tess.uv[2 * i], tess.uv[2 * i + 1]), c, 3 * i);
  } else {
    const k = Array.from(tess.mean, (x) => Math.abs(x)).sort((a, b) => a - b);
    curvatureScale = k[Math.floor(0.95 * (k.length - 1))] || 1;
    for (let i = 0; i < n; i++) curvatureColour(tess.mean[i] / curvatureScale, c, 3 * i);
  }
  return c;
}

// The surface's mesh: its buffers are updated in place while the grid keeps its size and
// the colouring its kind (a drag); the basis values at the samples are kept (Tessellator).
const tessellator = new Tessellator();
let surfaceKind = "";
function gridIndex(su, sv) {
  const index = new (su * sv > 65535 ? Uint32Array : Uint16Array)(6 * (su - 1) * (sv - 1));
  let k = 0;
  for (let i = 0; i + 1 < su; i++)
    for (let j = 0; j + 1 < sv; j++) {
      const a = i * sv + j, b = a + sv;
      index[k++] = a; index[k++] = b; index[k++] = a + 1;
      index[k++] = a + 1; index[k++] = b; index[k++] = b + 1;
    }
  return index;
}
export function buildSurface(final) {
  const st = S.state;
  const [su, sv] = final ? sampleCounts(st.surface, 12, 240) : sampleCounts(st.surface, 3, 48);
  const mode = $("mode").value;
  const coloured = mode === "deviation" || mode === "curvature";
  tess = tessellator.run(st.surface, su, sv, S.centre, mode === "curvature");
  const kind = `${su}x${sv}:${coloured}`;
  const mat = mode === "zebra" ? zebraMaterial : mode === "shaded" ? shadedMaterial : colouredMaterial;
  if (surfaceMesh && kind === surfaceKind) {
    const g = surfaceMesh.geometry;
    g.attributes.position.needsUpdate = true;  // the tessellator wrote into these arrays
    g.attributes.normal.needsUpdate = true;
    if (coloured) {
      g.attributes.color.array.set(surfaceColours(mode));
      g.attributes.color.needsUpdate = true;
    }
    g.computeBoundingSphere();
    surfaceMesh.material = mat;
  } else {
    const g = new THREE.BufferGeometry();
    g.setAttribute("position", new THREE.BufferAttribute(tess.position, 3).setUsage(THREE.DynamicDrawUsage));
    g.setAttribute("normal", new THREE.BufferAttribute(tess.normal, 3).setUsage(THREE.DynamicDrawUsage));
    g.setIndex(new THREE.BufferAttribute(gridIndex(su, sv), 1));
    if (coloured)
      g.setAttribute("color", new THREE.BufferAttribute(surfaceColours(mode), 3).setUsage(THREE.DynamicDrawUsage));
    if (surfaceMesh) { world.remove(surfaceMesh); surfaceMesh.geometry.dispose(); }
    surfaceMesh = new THREE.Mesh(g, mat);
    world.add(surfaceMesh);
    surfaceKind = kind;
  }
  if (final || !$("net").checked) buildNet(); else moveNet();
  showLegend(mode, st, curvatureScale);
}

// The control net: lines and points, drawn after the surface (render order) and depth-tested
// against it (the surface is offset back), so the net on the near side is never hidden by the
// surface it shapes.
let netShape = "";
export function buildNet() {
  for (const o of [netLines, netPoints]) if (o) { world.remove(o); o.geometry.dispose(); }
  netLines = netPoints = null;
  netShape = "";
  if (!$("net").checked || !S.state) return;
  const cp = S.state.surface.control_points, v = [], pts = [];
  const push = (p) => v.push(p[0] - S.centre[0], p[1] - S.centre[1], p[2] - S.centre[2]);
  for (let i = 0; i < cp.length; i++)
    for (let j = 0; j < cp[i].length; j++) {
      pts.push(cp[i][j][0] - S.centre[0], cp[i][j][1] - S.centre[1], cp[i][j][2] - S.centre[2]);
      if (i + 1 < cp.length) { push(cp[i][j]); push(cp[i + 1][j]); }
      if (j + 1 < cp[i].length) { push(cp[i][j]); push(cp[i][j + 1]); }
    }
  const g = new THREE.BufferGeometry();
  g.setAttribute("position", new THREE.Float32BufferAttribute(v, 3));
  netLines = new THREE.LineSegments(g, new THREE.LineBasicMaterial({ color: 0xffc857 }));
  netLines.renderOrder = 1;
  world.add(netLines);
  const pg = new THREE.BufferGeometry();
  pg.setAttribute("position", new THREE.Float32BufferAttribute(pts, 3));
  netPoints = new THREE.Points(pg, new THREE.PointsMaterial({ color: 0xffa020, size: 6, sizeAttenuation: false }));
  netPoints.renderOrder = 1;
  world.add(netPoints);
  netShape = `${cp.length}x${cp[0].length}`;
}
function moveNet() {  // a drag at fixed counts: the same net, its points moved
  const cp = S.state.surface.control_points;
  if (!netLines || netShape !== `${cp.length}x${cp[0].length}`) return buildNet();
  const lp = netLines.geometry.attributes.position, pp = netPoints.geometry.attributes.position;
  const c = S.centre;
  let k = 0, m = 0;
  const set = (p) => { lp.setXYZ(k++, p[0] - c[0], p[1] - c[1], p[2] - c[2]); };
  for (let i = 0; i < cp.length; i++)
    for (let j = 0; j < cp[i].length; j++) {
      pp.setXYZ(m++, cp[i][j][0] - c[0], cp[i][j][1] - c[1], cp[i][j][2] - c[2]);
      if (i + 1 < cp.length) { set(cp[i][j]); set(cp[i + 1][j]); }
      if (j + 1 < cp[i].length) { set(cp[i][j]); set(cp[i][j + 1]); }
    }
  lp.needsUpdate = true; pp.needsUpdate = true;
}
/// The control point (i, j) nearest to `hit` in screen pixels (within `radius`), or null.
export function netPointNear(screenOf, x, y, radius = 8) {
  if (!netPoints || !S.state) return null;
  const cp = S.state.surface.control_points;
  let best = null, bestD = radius;
  cp.forEach((r, i) => r.forEach((p, j) => {
    const s = screenOf(p);
    if (s.z < -1 || s.z > 1) return;
    const d = Math.hypot(s.x - x, s.y - y);
    if (d < bestD) { bestD = d; best = { i, j, p }; }
  }));
  return best;
}

let firstOfRow = [];  // flat index of each row's first point in the point buffers
export function buildPoints() {
  for (const o of [pointsObj, rowLines]) if (o) { world.remove(o); o.geometry.dispose(); }
  const rows = S.rows, c = S.centre;
  firstOfRow = [];
  rows.reduce((s, r) => { firstOfRow.push(s); return s + r.length; }, 0);
  const n = rows.reduce((s, r) => s + r.length, 0);
  const pos = new Float32Array(3 * n), col = new Float32Array(3 * n), line = [];
  let k = 0;
  rows.forEach((r, j) => {
    r.forEach((p, i) => {
      for (let a = 0; a < 3; a++) pos[3 * k + a] = p[a] - c[a];
      deviationColour(S.dev[j] ? S.dev[j][i] : NaN, col, 3 * k);
      if (i > 0) line.push(...r[i - 1].map((x, a) => x - c[a]), ...p.map((x, a) => x - c[a]));
      k++;
    });
  });
  const g = new THREE.BufferGeometry();
  g.setAttribute("position", new THREE.BufferAttribute(pos, 3));
  g.setAttribute("color", new THREE.BufferAttribute(col, 3));
  pointsObj = new THREE.Points(g, new THREE.PointsMaterial({
    size: n > 5000 ? 3 : 7, sizeAttenuation: false, vertexColors: true }));
  pointsObj.visible = $("points").checked;
  pointsObj.renderOrder = 1;
  world.add(pointsObj);
  const lg = new THREE.BufferGeometry();
  lg.setAttribute("position", new THREE.Float32BufferAttribute(line, 3));
  rowLines = new THREE.LineSegments(lg, new THREE.LineBasicMaterial({ color: 0x7a8894 }));
  rowLines.visible = $("points").checked;
  world.add(rowLines);
}
// On software GL (SwiftShader pays per primitive) the 10^4 data points and their row lines
// cost most of a drag step's frame, the coarse surface little: while a point is dragged only
// its row and the rows beside it are drawn (`row`), all of them again (null) when the hand
// rests or lets go. Under 2000 points all are drawn.
export function dragDetail(row) {
  if (!pointsObj || !rowLines) return;
  const n = pointsObj.geometry.attributes.position.count;
  const on = row !== null && hook.softwareGL && n >= 2000 && firstOfRow[row] !== undefined;
  const r0 = on ? Math.max(0, row - 1) : 0, r1 = on ? Math.min(S.rows.length, row + 2) : S.rows.length;
  const first = (j) => (j < firstOfRow.length ? firstOfRow[j] : n);  // flat index of row j's first point
  const seg = (j) => first(j) - j;  // index of row j's first line segment
  const points = on ? [first(r0), first(r1) - first(r0)] : [0, Infinity];
  const lines = on ? [2 * seg(r0), 2 * (seg(r1) - seg(r0))] : [0, Infinity];
  const range = pointsObj.geometry.drawRange;
  if (range.start === points[0] && range.count === points[1]) return;  // no frame of its own
  pointsObj.geometry.setDrawRange(...points);
  rowLines.geometry.setDrawRange(...lines);
  redraw();
}
export function showPoints(on) {
  for (const o of [pointsObj, rowLines]) if (o) o.visible = on;
  redraw();
}

// Moves one drawn point (and its row's line) without rebuilding the buffers.
export function moveDrawnPoint(row, index, p) {
  const k = firstOfRow[row] + index;
  const q = p.map((x, a) => x - S.centre[a]);
  // Only the changed vertices are sent to the GPU (10^4 points are 360 kB with their lines).
  const pos = pointsObj.geometry.attributes.position;
  pos.setXYZ(k, q[0], q[1], q[2]);
  pos.addUpdateRange(3 * k, 3);
  pos.needsUpdate = true;
  const lp = rowLines.geometry.attributes.position;
  const seg = firstOfRow[row] - row + index - 1;  // the segment ending at this point
  if (index > 0) { lp.setXYZ(2 * seg + 1, q[0], q[1], q[2]); lp.addUpdateRange(3 * (2 * seg + 1), 3); }
  if (index + 1 < S.rows[row].length) { lp.setXYZ(2 * (seg + 1), q[0], q[1], q[2]); lp.addUpdateRange(3 * (2 * seg + 2), 3); }
  lp.needsUpdate = true;
}

// A marker: one point drawn on top, its buffer moved in place.
function markerAt(obj, p, colour, size) {
  if (!obj) {
    const g = new THREE.BufferGeometry();
    g.setAttribute("position", new THREE.BufferAttribute(new Float32Array(3), 3));
    obj = new THREE.Points(g, new THREE.PointsMaterial({
      size, sizeAttenuation: false, color: colour, depthTest: false, transparent: true, opacity: 0.9 }));
    obj.renderOrder = 3;
    obj.frustumCulled = false;
    world.add(obj);
  }
  obj.visible = !!p;
  if (p) {
    const a = obj.geometry.attributes.position;
    a.setXYZ(0, p[0] - S.centre[0], p[1] - S.centre[1], p[2] - S.centre[2]);
    a.needsUpdate = true;
  }
  return obj;
}

const pointAt = (sel) => (sel && S.rows[sel.row] && S.rows[sel.row][sel.index]) || null;
/// The worst and the selected point's markers; `fails`: the ring of every point over T too
/// (rebuilt only with a state that brings the points' deviations).
let overCount = 0;
export function updateMarkers(fails = false) {
  const w = S.state.report.worst;
  marker = markerAt(marker, pointAt({ row: w.row, index: w.index }), 0xff3030, 15);
  selMarker = markerAt(selMarker, pointAt(S.selected), 0xffff40, 12);
  if (!fails) return overCount;
  // Every point over T ringed (a file that does not fit at its T, or a quick refit that
  // misses it): where to look to fix it.
  if (failMarks) { world.remove(failMarks); failMarks.geometry.dispose(); failMarks = null; }
  const over = [];
  S.dev.forEach((r, j) => r && r.forEach((x, i) => { if (x > 1 && S.rows[j] && S.rows[j][i]) over.push(...S.rows[j][i].map((c, a) => c - S.centre[a])); }));
  if (over.length) {
    const g = new THREE.BufferGeometry();
    g.setAttribute("position", new THREE.Float32BufferAttribute(over, 3));
    failMarks = new THREE.Points(g, new THREE.PointsMaterial({ size: 13, sizeAttenuation: false, color: 0xff40ff,
      depthTest: false, transparent: true, opacity: 0.55 }));
    failMarks.renderOrder = 2;
    world.add(failMarks);
  }
  overCount = over.length / 3;
  return overCount;
}

// The drag's constraint: a translucent patch of its plane or a line along its axis, through
// the point where the drag started.
let gizmo = null;
const planeMaterial = new THREE.MeshBasicMaterial({ color: 0x40a0ff, transparent: true, opacity: 0.3,
  side: THREE.DoubleSide, depthWrite: false });
const axisMaterials = new Map();  // by colour
const axisMaterial = (colour) => axisMaterials.get(colour) ||
  axisMaterials.set(colour, new THREE.LineBasicMaterial({ color: colour, depthTest: false })).get(colour);
export function showConstraint(c, origin) {
  if (gizmo) { world.remove(gizmo); gizmo.geometry.dispose(); gizmo = null; }
  if (!c) return redraw();
  const size = S.diagonal * 0.18;
  if (c.kind === "plane") {
    const g = new THREE.PlaneGeometry(size, size);
    gizmo = new THREE.Mesh(g, planeMaterial);
    gizmo.quaternion.setFromUnitVectors(new THREE.Vector3(0, 0, 1), c.n);
  } else {
    const d = c.d.clone().multiplyScalar(S.diagonal);
    const g = new THREE.BufferGeometry().setFromPoints([d.clone().negate(), d]);
    gizmo = new THREE.Line(g, axisMaterial(c.colour || 0x40ffa0));
  }
  gizmo.position.copy(origin);
  gizmo.renderOrder = 2;
  gizmo.name = `constraint-${c.kind}`;
  world.add(gizmo);
  redraw();
}
export const constraintShown = () => (gizmo ? gizmo.name : null);
export { local };

/// Draws the constraint's plane once, unseen (opacity 0: the same shaders and the same
/// blending), before the first drag: a software rasteriser compiles a program and its
/// drawing state when they are first drawn, which made the first drag's first step wait
/// for a task of 175-190 ms (96-104 ms with this; the browser's long tasks, load 7).
export function warmUp(renderer, scene, camera) {
  const plane = new THREE.Mesh(new THREE.PlaneGeometry(S.diagonal * 0.18, S.diagonal * 0.18), planeMaterial);
  const opacity = planeMaterial.opacity;
  planeMaterial.opacity = 0;
  world.add(plane);
  renderer.render(scene, camera);
  world.remove(plane);
  plane.geometry.dispose();
  planeMaterial.opacity = opacity;
  redraw();
}
