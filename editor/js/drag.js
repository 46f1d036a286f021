// Select, then drag (docs/editor.md, "Editing"): a click selects a point; only a drag that
// starts on the selected point moves it, any other left drag orbits (right: pan, wheel: zoom
// to the cursor). A drag is constrained as in Rhino: in the row's own plane (the best plane
// of the row: a station's or a blade section's plane), along the surface normal, along x, y
// or z, or in the view plane; the constraint is drawn while dragging. Tab locks the direction
// moved so far (again: unlocks), Esc cancels the drag (the point back where it was), the
// arrow keys nudge the selected point by the step (Shift 10x, Alt 0.1x), F fits the view.
import * as THREE from "three";
import { $, S, hook } from "./store.js";
import { canvas, controls, camera, coarseImage, redraw, screenOf, rayOf, local, global, fitView } from "./view.js";
import { moveDrawnPoint, updateMarkers, showConstraint, netPointNear, dragDetail } from "./draw.js";
import { evaluate } from "./bspline.js";
import * as predict from "./predict.js";

const PICK_PX = 12;
export function pick(x, y) {
  let best = null, bestD = PICK_PX;
  S.rows.forEach((r, j) => r.forEach((p, i) => {
    const s = screenOf(p);
    if (s.z < -1 || s.z > 1) return;
    const d = Math.hypot(s.x - x, s.y - y);
    if (d < bestD) { bestD = d; best = { row: j, index: i }; }
  }));
  return best;
}

// Eigen-decomposition of a symmetric 3 x 3 matrix (Jacobi rotations): [values, vectors].
function eigenSym3(A) {
  const a = A.map((r) => r.slice()), V = [[1, 0, 0], [0, 1, 0], [0, 0, 1]];
  for (let sweep = 0; sweep < 50; sweep++) {
    const off = Math.abs(a[0][1]) + Math.abs(a[0][2]) + Math.abs(a[1][2]);
    if (off < 1e-300) break;
    for (const [p, q] of [[0, 1], [0, 2], [1, 2]]) {
      if (Math.abs(a[p][q]) < 1e-300) continue;
      const th = (a[q][q] - a[p][p]) / (2 * a[p][q]);
      const t = Math.sign(th || 1) / (Math.abs(th) + Math.sqrt(th * th + 1));
      const c = 1 / Math.sqrt(t * t + 1), s = t * c;
      for (let k = 0; k < 3; k++) {  // columns p, q
        const akp = a[k][p], akq = a[k][q];
        a[k][p] = c * akp - s * akq; a[k][q] = s * akp + c * akq;
      }
      for (let k = 0; k < 3; k++) {  // rows p, q
        const apk = a[p][k], aqk = a[q][k];
        a[p][k] = c * apk - s * aqk; a[q][k] = s * apk + c * aqk;
      }
      for (let k = 0; k < 3; k++) {
        const vkp = V[k][p], vkq = V[k][q];
        V[k][p] = c * vkp - s * vkq; V[k][q] = s * vkp + c * vkq;
      }
    }
  }
  return [[a[0][0], a[1][1], a[2][2]], V];
}

/// The normal of the row's best plane (least variance of its points), or null when the row
/// is (nearly) straight or has fewer than 3 points: no plane to keep.
export function rowPlaneNormal(row) {
  const pts = S.rows[row];
  if (!pts || pts.length < 3) return null;
  const m = [0, 0, 0];
  for (const p of pts) for (let a = 0; a < 3; a++) m[a] += p[a] / pts.length;
  const C = [[0, 0, 0], [0, 0, 0], [0, 0, 0]];
  for (const p of pts) for (let a = 0; a < 3; a++) for (let b = 0; b < 3; b++) C[a][b] += (p[a] - m[a]) * (p[b] - m[b]);
  const [vals, V] = eigenSym3(C);
  const order = [0, 1, 2].sort((x, y) => vals[x] - vals[y]);
  if (!(vals[order[1]] > 1e-10 * vals[order[2]])) return null;
  const n = new THREE.Vector3(V[0][order[0]], V[1][order[0]], V[2][order[0]]).normalize();
  // A station's plane is x = const up to round-off: snapped to the axis, x is kept exactly.
  for (let a = 0; a < 3; a++)
    if (Math.abs(n.getComponent(a)) > 1 - 1e-12) return new THREE.Vector3(...[0, 1, 2].map((b) => (b === a ? 1 : 0)));
  return n;
}

/// The unit surface normal at the point's parameters (finite differences of the surface).
function surfaceNormal(row, index) {
  const st = S.state, sf = st.surface;
  if (!S.params || !S.params.u[row]) return null;
  const u = S.params.u[row][index];
  const v = S.params.vp ? S.params.vp[row][index] : S.params.v[row];
  const dom = (k, p) => [k[p], k[k.length - p - 1]];
  const [u0, u1] = dom(sf.knots_u, sf.degree[0]), [v0, v1] = dom(sf.knots_v, sf.degree[1]);
  const hu = 1e-5 * (u1 - u0), hv = 1e-5 * (v1 - v0);
  const cl = (x, a, b) => Math.min(b, Math.max(a, x));
  const P = (uu, vv) => new THREE.Vector3(...evaluate(sf, cl(uu, u0, u1), cl(vv, v0, v1)));
  const su = P(u + hu, v).sub(P(u - hu, v)), sv = P(u, v + hv).sub(P(u, v - hv));
  const n = su.cross(sv);
  return n.lengthSq() > 0 ? n.normalize() : null;
}

const viewNormal = () => { const n = new THREE.Vector3(); camera.getWorldDirection(n); return n; };
const AXES = { x: [1, 0, 0], y: [0, 1, 0], z: [0, 0, 1] };
/// The constraint of mode `mode` for point (row, index): {kind: "plane", n} or {kind: "line", d}.
export function constraintFor(mode, row, index) {
  if (mode === "row") {
    const n = rowPlaneNormal(row);
    return n ? { kind: "plane", n, label: "row plane" } : { kind: "plane", n: viewNormal(), label: "view plane (the row is straight)" };
  }
  if (mode === "normal") {
    const d = surfaceNormal(row, index);
    return d ? { kind: "line", d, label: "surface normal" } : { kind: "plane", n: viewNormal(), label: "view plane" };
  }
  if (AXES[mode]) return { kind: "line", d: new THREE.Vector3(...AXES[mode]), label: `along ${mode}`, colour: [0xff5050, 0x50ff50, 0x5080ff][Object.keys(AXES).indexOf(mode)] };
  return { kind: "plane", n: viewNormal(), label: "view plane" };
}

function keptAxes(c) {
  const v = c.kind === "plane" ? c.n : c.d;
  const axis = [0, 1, 2].find((a) => Math.abs(v.getComponent(a)) === 1 &&
    [0, 1, 2].every((b) => b === a || v.getComponent(b) === 0));
  if (axis === undefined) return [];
  return c.kind === "plane" ? [axis] : [0, 1, 2].filter((b) => b !== axis);
}

function targetOn(c, origin, ray) {
  if (c.kind === "plane") {
    const hit = new THREE.Vector3();
    return ray.intersectPlane(new THREE.Plane().setFromNormalAndCoplanarPoint(c.n, origin), hit) ? hit : null;
  }
  // The point of the line through `origin` nearest to the ray.
  const a = c.d, w0 = origin.clone().sub(ray.origin), d = ray.direction;
  const b = a.dot(d), dd = a.dot(w0), e2 = d.dot(w0), den = 1 - b * b;
  if (Math.abs(den) < 1e-9) return null;
  return origin.clone().addScaledVector(a, (b * e2 - dd) / den);
}

// ---- the drag ----------------------------------------------------------------------------
S.drag = null;  // {row, index, start (data coords), origin (view coords), base, c, last, locked}
let down = null;  // a left press not on the selected point: a click if it does not move

function setPoint(row, index, p) {
  S.rows[row][index] = p;
  moveDrawnPoint(row, index, p);
  S.fns.showCoords(p);
  updateMarkers();
}

function beginDrag(hit, e) {
  const p = S.rows[hit.row][hit.index];
  const base = constraintFor($("axis").value, hit.row, hit.index);
  S.drag = { ...hit, start: p.slice(), origin: local(p), base, c: base, last: null, locked: false, pred: null };
  // The refit predicted in the page where it is linear (predict.js): from the first move, or
  // from the move under way when the influence arrives during the drag.
  const drag = S.drag;
  const ready = predict.forDrag(hit.row, hit.index, S.state.version, (k) => {
    if (S.drag !== drag) return;
    drag.pred = k;
    if (drag.last) S.fns.showPrediction({ to: drag.last.to, t: drag.lastT });
  });
  // A full search under way (the hold's) holds the session, the influence waits behind it:
  // the drag's first step would drop it anyway.
  if (!ready) S.fns.dropStaleSearch();
  controls.enabled = false;
  coarseImage(true);
  dragDetail(hit.row);  // the press's own frame is already the light one of the drag
  S.fns.coarseSurface();  // and draws the drag's coarse tessellation (a new mesh, slow to draw first)
  showConstraint(base, S.drag.origin);
  S.fns.message(`dragging in the ${base.label}: Tab locks the direction, Esc cancels`, true);
  canvas.setPointerCapture(e.pointerId);
}

canvas.addEventListener("pointerdown", (e) => {
  if (e.button !== 0 || !S.state) return;
  const hit = pick(e.clientX, e.clientY);
  const sel = S.selected;
  if (hit && sel && hit.row === sel.row && hit.index === sel.index && !S.fns.readOnlyEdits?.()) {
    beginDrag(hit, e);
    e.stopImmediatePropagation();  // not an orbit
    e.preventDefault();
    return;
  }
  down = { x: e.clientX, y: e.clientY, hit };
}, { capture: true });

// pointerrawupdate where the browser has it: Chromium delivers pointermove only with the next
// animation frame, the raw event as soon as the hand moves.
const moveEvent = "onpointerrawupdate" in window ? "pointerrawupdate" : "pointermove";
canvas.addEventListener(moveEvent, (e) => {
  const d = S.drag;
  if (!d) return;
  d.lastEvent = { clientX: e.clientX, clientY: e.clientY };
  const q = targetOn(d.c, d.origin, rayOf(e));
  if (!q) return;
  const to = global(q);
  // Coordinates the constraint keeps (an axis plane's, an axis line's others) are kept
  // exactly, not recomputed through the ray (the view's offset and round-off).
  for (const a of keptAxes(d.c)) to[a] = d.start[a];
  dragDetail(d.row);  // the other rows' points come back when the hand rests
  setPoint(d.row, d.index, to);
  d.last = { row: d.row, index: d.index, to };
  d.lastT = e.timeStamp;
  hook.moves.push(e.timeStamp);
  if (d.pred) S.fns.showPrediction({ to, t: e.timeStamp });
  S.fns.queueMove({ row: d.row, index: d.index, to, phase: "drag", t: e.timeStamp, pk: d.pred || undefined });
  // Drawn with the refit of this step (or a newer one), whose answer comes next: a frame of
  // the moved point alone would only delay that one on a software rasteriser. Nor while the
  // influence asked for is on its way (the prediction draws the newest move when it comes):
  // the frames would take the cores its factorisation needs (docs/editor-latency.md).
  if (!d.pred && !S.fns.moveInFlight() && !predict.asked()) redraw();
});

function finishDrag() {
  const d = S.drag;
  S.drag = null;
  predict.dropDrag();
  controls.enabled = true;
  coarseImage(false);
  dragDetail(null);
  showConstraint(null);
  return d;
}
function endDrag(e) {
  if (S.drag) {
    const d = finishDrag();
    S.fns.message("");
    if (d.last) {
      S.fns.queueMove({ ...d.last, phase: "end", t: e.timeStamp });
      S.fns.checkNear(d.row, d.index, d.last.to);
    }
    return;
  }
  if (down && e.type === "pointerup" && Math.hypot(e.clientX - down.x, e.clientY - down.y) < 5) select(down, e);
  down = null;
}
canvas.addEventListener("pointerup", endDrag);
canvas.addEventListener("pointercancel", endDrag);

export function cancelDrag() {
  const d = finishDrag();
  if (!d) return;
  setPoint(d.row, d.index, d.start);
  if (d.last) S.fns.queueMove({ row: d.row, index: d.index, to: d.start, phase: "end" });
  S.fns.message("drag cancelled: the point is back where it was", true);
  redraw();
}

function select(click) {
  if (click.hit) {
    S.selected = click.hit;
    S.fns.showSelection();
  } else {
    const cp = netPointNear(screenOf, click.x, click.y);
    S.selected = null;
    S.fns.showSelection();
    if (cp) S.fns.message(`control point (${cp.i}, ${cp.j}): ${cp.p.map((x) => x.toPrecision(6)).join(", ")}`, true);
  }
  updateMarkers();
  redraw();
  predict.prefetch();  // the influence of the selected point, for its drag
}

// Tab: the direction moved so far becomes the drag's line (again: the constraint returns).
function toggleLock() {
  const d = S.drag;
  if (d.locked) {
    d.c = d.base; d.locked = false;
  } else {
    const now = local(S.rows[d.row][d.index]).sub(d.origin);
    if (!(now.lengthSq() > 0)) return S.fns.message("move first: Tab locks the direction moved so far");
    d.c = { kind: "line", d: now.normalize(), label: "locked direction", colour: 0xff9040 };
    d.locked = true;
  }
  showConstraint(d.c, d.origin);
  S.fns.message(d.locked ? "direction locked (Tab unlocks)" : `dragging in the ${d.base.label}`, true);
}

// ---- nudges: the arrow keys move the selected point by the step --------------------------
let nudgeTimer = null, nudgeStart = null;
function nudge(key, e) {
  const sel = S.selected;
  const c = constraintFor($("axis").value, sel.row, sel.index);
  let dir;
  if (c.kind === "line") {
    dir = c.d.clone().multiplyScalar(key === "ArrowRight" || key === "ArrowUp" ? 1 : -1);
  } else {
    const right = new THREE.Vector3().setFromMatrixColumn(camera.matrixWorld, 0);
    const a1 = right.clone().addScaledVector(c.n, -right.dot(c.n));
    if (a1.lengthSq() < 1e-12) a1.set(1, 0, 0).addScaledVector(c.n, -c.n.x);
    a1.normalize();
    const a2 = new THREE.Vector3().crossVectors(c.n, a1);
    const up = new THREE.Vector3().setFromMatrixColumn(camera.matrixWorld, 1);
    if (a2.dot(up) < 0) a2.negate();
    dir = { ArrowRight: a1, ArrowLeft: a1.clone().negate(), ArrowUp: a2, ArrowDown: a2.clone().negate() }[key];
  }
  const step = S.fns.step() * (e.shiftKey ? 10 : e.altKey ? 0.1 : 1);
  const p = S.rows[sel.row][sel.index];
  if (!nudgeStart) nudgeStart = { row: sel.row, index: sel.index };
  const to = [p[0] + step * dir.x, p[1] + step * dir.y, p[2] + step * dir.z];
  setPoint(sel.row, sel.index, to);
  S.fns.queueMove({ row: sel.row, index: sel.index, to, phase: "drag", t: e.timeStamp });
  redraw();
  clearTimeout(nudgeTimer);
  nudgeTimer = setTimeout(() => {  // the nudges of one burst are one undo step
    nudgeStart = null;
    const q = S.rows[sel.row][sel.index];
    S.fns.queueMove({ row: sel.row, index: sel.index, to: q, phase: "end" });
    S.fns.checkNear(sel.row, sel.index, q);
  }, 400);
}
export const nudging = () => nudgeStart !== null;

window.addEventListener("keydown", (e) => {
  const t = e.target;
  if (t instanceof HTMLInputElement && t.type !== "checkbox" && t.type !== "range") return;
  if (t instanceof HTMLSelectElement && e.key.startsWith("Arrow")) return;
  if (S.drag) {
    if (e.key === "Tab") { e.preventDefault(); toggleLock(); }
    else if (e.key === "Escape") { e.preventDefault(); cancelDrag(); }
    return;
  }
  if (e.ctrlKey || e.metaKey) return;
  if ((e.key === "f" || e.key === "F") && !e.altKey) { e.preventDefault(); fitView(false); }
  else if (e.key.startsWith("Arrow") && S.selected && !S.fns.readOnlyEdits?.()) { e.preventDefault(); nudge(e.key, e); }
  else if (e.key === "Escape" && S.selected) { S.selected = null; S.fns.showSelection(); updateMarkers(); redraw(); }
});

// For tests: the constraint of the selected point, the drag, the camera.
hook.constraintOf = (row, index) => {
  const c = constraintFor($("axis").value, row, index);
  return { kind: c.kind, label: c.label, v: (c.kind === "plane" ? c.n : c.d).toArray() };
};
hook.dragging = () => (S.drag ? { row: S.drag.row, index: S.drag.index, locked: S.drag.locked } : null);
hook.camera = () => ({ position: camera.position.toArray(), target: controls.target.toArray() });
