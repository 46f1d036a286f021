// The editor page: the rows and the surface in a three.js view; edits go to the server's
// JSON API (docs/editor.md), which refits through IncrementalFit.
import * as THREE from "three";
import { OrbitControls } from "three/addons/controls/OrbitControls.js";
import * as api from "./api.js";
import { sampleCounts, Tessellator } from "./bspline.js";
import { curvatureColour, deviationColour } from "./colours.js";

const $ = (id) => document.getElementById(id);
// For tests and benchmarks: the last state, frames drawn, move-to-frame latencies, the
// times of the drag's mouse events; restMs: how long the hand rests before the full fit.
const hook = (window.sfitEditor = { state: null, frames: 0, latencies: [], moves: [], ready: false, restMs: 250 });

// ---- the view ----------------------------------------------------------------------------
const view = $("view");
// On a software rasteriser (SwiftShader, llvmpipe) multisampling costs most of each frame.
function softwareGL() {
  const gl = document.createElement("canvas").getContext("webgl2");
  const info = gl && gl.getExtension("WEBGL_debug_renderer_info");
  const name = info ? String(gl.getParameter(info.UNMASKED_RENDERER_WEBGL)) : "";
  if (gl) gl.getExtension("WEBGL_lose_context")?.loseContext();
  return /swiftshader|llvmpipe|software/i.test(name);
}
hook.softwareGL = softwareGL();
const renderer = new THREE.WebGLRenderer({ antialias: !hook.softwareGL, preserveDrawingBuffer: true });
renderer.setPixelRatio(window.devicePixelRatio || 1);
view.appendChild(renderer.domElement);
const scene = new THREE.Scene();
scene.background = new THREE.Color(0x1d2024);
const camera = new THREE.PerspectiveCamera(40, 1, 0.001, 1000);
const controls = new OrbitControls(camera, renderer.domElement);
scene.add(new THREE.HemisphereLight(0xffffff, 0x404050, 1.6));
const sun = new THREE.DirectionalLight(0xffffff, 1.4);
scene.add(sun);
const world = new THREE.Group();  // data coordinates less `centre`
scene.add(world);

let needsRender = true;
let frameWaiters = [];
controls.addEventListener("change", () => (needsRender = true));
// On software GL the pixels dominate a frame: while a point is dragged the view is drawn at
// half resolution (the quick image), at full resolution again when the hand lets go.
function coarseImage(on) {
  if (!hook.softwareGL) return;
  renderer.setPixelRatio((window.devicePixelRatio || 1) * (on ? 0.5 : 1));
  resize();
}
function resize() {
  const w = view.clientWidth, h = view.clientHeight;
  renderer.setSize(w, h);
  camera.aspect = w / Math.max(1, h);
  camera.updateProjectionMatrix();
  needsRender = true;
}
window.addEventListener("resize", resize);
// Calls `done(time)` once the GPU (the software rasteriser on SwiftShader) has finished the
// commands issued so far, i.e. the frame is drawn, not merely submitted: a WebGL2 fence,
// polled from the event loop (WebGL updates a fence's status only between tasks).
const gl = renderer.getContext();
function whenDrawn(done) {
  if (typeof WebGL2RenderingContext === "undefined" || !(gl instanceof WebGL2RenderingContext)) {
    done(performance.now());
    return;
  }
  const sync = gl.fenceSync(gl.SYNC_GPU_COMMANDS_COMPLETE, 0);
  gl.flush();
  const poll = () => {
    if (gl.getSyncParameter(sync, gl.SYNC_STATUS) !== gl.SIGNALED) return void setTimeout(poll, 1);
    gl.deleteSync(sync);
    done(performance.now());
  };
  setTimeout(poll, 0);
}
// Frames are drawn on demand, at most one at a time: while the GPU (on software GL, the
// CPU) still draws the last one, nothing new is issued, so frames never queue up behind each
// other; a refitted state that arrived meanwhile waits, and only the newest is drawn. A drag's
// refitted state is drawn as soon as it arrives (or the frame before it is done), not at the
// next animation frame: the compositor shows it at its next frame either way.
let drawing = false, incoming = null;  // incoming: the newest refitted drag state, not yet shown
function loop() {
  requestAnimationFrame(loop);
  frame();
}
function frame() {
  if (drawing) return;
  if (incoming) {
    const { st, job } = incoming;
    incoming = null;
    if (!state || st.version >= state.version) applyState(st, job);
  }
  if (!needsRender) return;
  needsRender = false;
  sun.position.copy(camera.position);
  const t0 = performance.now();
  renderer.render(scene, camera);
  hook.renderMs = performance.now() - t0;
  hook.frames++;
  drawing = true;
  const waiters = frameWaiters;
  frameWaiters = [];
  whenDrawn((drawn) => {
    drawing = false;
    hook.drawMs = drawn - t0;
    // Shown: the next animation frame after the drawing is done is the one that hands the
    // canvas to the compositor (which displays it with that frame).
    if (waiters.length) requestAnimationFrame(() => { const now = performance.now(); for (const f of waiters) f(now, t0, drawn); });
    if (incoming) frame();
  });
}

// ---- what is shown -----------------------------------------------------------------------
let state = null;      // the last state from the server
let rows = [];         // [[x, y, z], ...] per row
let dev = [];          // per point fraction of T used
let params = null;     // {u: per row, v}
let centre = [0, 0, 0];
let diagonal = 1;
let selected = null;   // {row, index}
let surfaceMesh = null, pointsObj = null, rowLines = null, netLines = null, marker = null;
let selMarker = null, tess = null;

const zebraMaterial = new THREE.ShaderMaterial({
  side: THREE.DoubleSide,
  vertexShader: `varying vec3 vN; varying vec3 vP;
    void main() { vN = normalize(normalMatrix * normal); vec4 p = modelViewMatrix * vec4(position, 1.0);
      vP = p.xyz; gl_Position = projectionMatrix * p; }`,
  fragmentShader: `varying vec3 vN; varying vec3 vP;
    void main() { vec3 r = reflect(normalize(vP), normalize(vN));
      float s = step(0.5, fract(6.0 * (r.y * 0.5 + 0.5)));
      gl_FragColor = vec4(vec3(0.08 + 0.85 * s), 1.0); }`,
});
// Phong, not the physically based MeshStandardMaterial: far cheaper per pixel on software GL.
const shadedMaterial = new THREE.MeshPhongMaterial({
  color: 0x8fb3d9, side: THREE.DoubleSide, shininess: 40, specular: 0x333333,
  polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1 });
const colouredMaterial = new THREE.MeshPhongMaterial({
  vertexColors: true, side: THREE.DoubleSide, shininess: 20, specular: 0x222222,
  polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1 });

function boxOf(rs) {
  const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
  for (const r of rs) for (const p of r) for (let a = 0; a < 3; a++) {
    lo[a] = Math.min(lo[a], p[a]); hi[a] = Math.max(hi[a], p[a]);
  }
  return { lo, hi };
}

function frameCamera() {
  const { lo, hi } = boxOf(rows);
  centre = [0, 1, 2].map((a) => (lo[a] + hi[a]) / 2);
  diagonal = Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]) || 1;
  camera.near = diagonal / 1000; camera.far = diagonal * 20;
  camera.position.set(0.7 * diagonal, -0.85 * diagonal, 0.65 * diagonal);
  camera.up.set(0, 0, 1);
  controls.target.set(0, 0, 0);
  camera.updateProjectionMatrix();
  controls.update();
}

// Fraction of T used at (u, v) of the surface: from the nearest points of the two rows
// around v, blended along v.
function deviationAt(u, v) {
  const vs = params.v;
  let j = 0;
  while (j + 1 < vs.length && vs[j + 1] <= v) j++;
  const near = (r) => {
    const us = params.u[r];
    let lo = 0, hi = us.length - 1;
    while (hi - lo > 1) { const m = (lo + hi) >> 1; if (us[m] <= u) lo = m; else hi = m; }
    return Math.abs(us[lo] - u) <= Math.abs(us[hi] - u) ? dev[r][lo] : dev[r][hi];
  };
  if (j + 1 >= vs.length || vs[j + 1] === vs[j]) return near(j);
  const t = Math.max(0, Math.min(1, (v - vs[j]) / (vs[j + 1] - vs[j])));
  return (1 - t) * near(j) + t * near(j + 1);
}

function surfaceColours(mode) {
  const n = tess.su * tess.sv, c = new Float32Array(3 * n);
  if (mode === "deviation" && params && dev.length) {
    for (let i = 0; i < n; i++) deviationColour(deviationAt(tess.uv[2 * i], tess.uv[2 * i + 1]), c, 3 * i);
  } else {
    const k = Array.from(tess.mean, (x) => Math.abs(x)).sort((a, b) => a - b);
    const scale = k[Math.floor(0.95 * (k.length - 1))] || 1;
    for (let i = 0; i < n; i++) curvatureColour(tess.mean[i] / scale, c, 3 * i);
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
function buildSurface(final) {
  const [su, sv] = final ? sampleCounts(state.surface, 12, 240) : sampleCounts(state.surface, 3, 48);
  const mode = $("mode").value;
  const coloured = mode === "deviation" || mode === "curvature";
  tess = tessellator.run(state.surface, su, sv, centre, mode === "curvature");
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
  buildNet();
}

function buildNet() {
  if (netLines) { world.remove(netLines); netLines.geometry.dispose(); netLines = null; }
  if (!$("net").checked) return;
  const cp = state.surface.control_points, v = [];
  const push = (p) => v.push(p[0] - centre[0], p[1] - centre[1], p[2] - centre[2]);
  for (let i = 0; i < cp.length; i++)
    for (let j = 0; j < cp[i].length; j++) {
      if (i + 1 < cp.length) { push(cp[i][j]); push(cp[i + 1][j]); }
      if (j + 1 < cp[i].length) { push(cp[i][j]); push(cp[i][j + 1]); }
    }
  const g = new THREE.BufferGeometry();
  g.setAttribute("position", new THREE.Float32BufferAttribute(v, 3));
  netLines = new THREE.LineSegments(g, new THREE.LineBasicMaterial({ color: 0xffc857 }));
  world.add(netLines);
}

let firstOfRow = [];  // flat index of each row's first point in the point buffers
function buildPoints() {
  for (const o of [pointsObj, rowLines]) if (o) { world.remove(o); o.geometry.dispose(); }
  firstOfRow = [];
  rows.reduce((s, r) => { firstOfRow.push(s); return s + r.length; }, 0);
  const n = rows.reduce((s, r) => s + r.length, 0);
  const pos = new Float32Array(3 * n), col = new Float32Array(3 * n), line = [];
  let k = 0;
  rows.forEach((r, j) => {
    r.forEach((p, i) => {
      for (let a = 0; a < 3; a++) pos[3 * k + a] = p[a] - centre[a];
      deviationColour(dev[j] ? dev[j][i] : NaN, col, 3 * k);
      if (i > 0) line.push(...r[i - 1].map((x, a) => x - centre[a]), ...p.map((x, a) => x - centre[a]));
      k++;
    });
  });
  const g = new THREE.BufferGeometry();
  g.setAttribute("position", new THREE.BufferAttribute(pos, 3));
  g.setAttribute("color", new THREE.BufferAttribute(col, 3));
  pointsObj = new THREE.Points(g, new THREE.PointsMaterial({
    size: n > 5000 ? 3 : 7, sizeAttenuation: false, vertexColors: true }));
  pointsObj.visible = $("points").checked;
  world.add(pointsObj);
  const lg = new THREE.BufferGeometry();
  lg.setAttribute("position", new THREE.Float32BufferAttribute(line, 3));
  rowLines = new THREE.LineSegments(lg, new THREE.LineBasicMaterial({ color: 0x7a8894 }));
  rowLines.visible = $("points").checked;
  world.add(rowLines);
}

// Moves one drawn point (and its row's line) without rebuilding the buffers.
function moveDrawnPoint(row, index, p) {
  const k = firstOfRow[row] + index;
  const q = p.map((x, a) => x - centre[a]);
  // Only the changed vertices are sent to the GPU (10^4 points are 360 kB with their lines).
  const pos = pointsObj.geometry.attributes.position;
  pos.setXYZ(k, q[0], q[1], q[2]);
  pos.addUpdateRange(3 * k, 3);
  pos.needsUpdate = true;
  const lp = rowLines.geometry.attributes.position;
  const seg = firstOfRow[row] - row + index - 1;  // the segment ending at this point
  if (index > 0) { lp.setXYZ(2 * seg + 1, q[0], q[1], q[2]); lp.addUpdateRange(3 * (2 * seg + 1), 3); }
  if (index + 1 < rows[row].length) { lp.setXYZ(2 * (seg + 1), q[0], q[1], q[2]); lp.addUpdateRange(3 * (2 * seg + 2), 3); }
  lp.needsUpdate = true;
}

// A marker: one point drawn on top, its buffer moved in place.
function markerAt(obj, p, colour, size) {
  if (!obj) {
    const g = new THREE.BufferGeometry();
    g.setAttribute("position", new THREE.BufferAttribute(new Float32Array(3), 3));
    obj = new THREE.Points(g, new THREE.PointsMaterial({
      size, sizeAttenuation: false, color: colour, depthTest: false, transparent: true, opacity: 0.9 }));
    obj.renderOrder = 2;
    obj.frustumCulled = false;
    world.add(obj);
  }
  obj.visible = !!p;
  if (p) {
    const a = obj.geometry.attributes.position;
    a.setXYZ(0, p[0] - centre[0], p[1] - centre[1], p[2] - centre[2]);
    a.needsUpdate = true;
  }
  return obj;
}

function updateMarkers() {
  const w = state.report.worst;
  marker = markerAt(marker, w.row >= 0 && rows[w.row] ? rows[w.row][w.index] : null, 0xff3030, 15);
  selMarker = markerAt(selMarker, selected ? rows[selected.row][selected.index] : null, 0xffff40, 12);
}

const g4 = (x) => (Math.abs(x) >= 1e4 || (Math.abs(x) < 1e-3 && x !== 0) ? x.toExponential(3) : x.toPrecision(4));
const vec = (p) => `${g4(p[0])}, ${g4(p[1])}, ${g4(p[2])}`;

// The report's cells are made once and only their changed texts set: on software GL a page
// whose layout changes is re-rastered in the same process that draws the view.
const setText = (el, text) => { if (el.textContent !== text) el.textContent = text; };
const setClass = (el, name) => { if (el.className !== name) el.className = name; };
let reportCells = null;
function showReport() {
  const r = state.report, d = state.deviation;
  const used = d.used === null ? "∞" : (100 * d.used).toFixed(1);
  if (!reportCells) {
    const names = ["control points", "points", "max deviation", "T", "used", "worst point", "parameters"];
    $("report").innerHTML = "<table>" + names.map((n) => `<tr><td>${n}</td><td></td></tr>`).join("") + "</table>";
    reportCells = Array.from($("report").querySelectorAll("tr td:nth-child(2)"));
  }
  const c = reportCells;
  setText(c[0], `${r.control_points[0]} × ${r.control_points[1]} (degree ${r.degree[0]} × ${r.degree[1]})`);
  setText(c[1], `${r.points} in ${r.rows} rows`);
  setText(c[2], vec(d.max));
  setText(c[3], vec(d.tolerance));
  setText(c[4], `${used}% of T: ${d.within ? "within T" : "NOT within T"}`);
  setClass(c[4], d.within ? "within" : "out");
  setText(c[5], `row ${r.worst.row}, point ${r.worst.index} (red)`);
  setText(c[6], `${r.parameters}; ${r.solves} solves, ${(1000 * r.seconds).toFixed(2)} ms`);
  const s = $("status");
  if (!d.within && !state.final) {
    setClass(s, "status quick over");
    setText(s, `quick refit at the current counts, every point checked: ${used}% of T, over T at the worst point; ` +
      "the final fit (more control points where needed) follows when you pause");
  } else if (!d.within) { setClass(s, "status bad"); setText(s, "NOT within T: see the worst point"); }
  else if (state.final) {
    setClass(s, "status");
    setText(s, `final surface: fewest control points, every point checked (max ${used}% of T)`);
  } else {
    setClass(s, "status quick");
    setText(s, `quick refit at the current counts (every point checked, max ${used}% of T); the final one follows when you pause`);
  }
  setText($("depths"), `${state.undo} undo, ${state.redo} redo`);
}

function showOptions() {
  const o = state.options;
  const t = Math.max(...o.tolerance);
  $("tol").value = t > 0 ? Math.log10(t / diagonal) : -6;
  $("tolText").textContent = g4(t);
  $("degU").value = o.degree[0]; $("degV").value = o.degree[1];
  $("closedU").checked = o.closed[0]; $("closedV").checked = o.closed[1];
  $("params").value = o.parameters; $("search").value = o.search === "linear" ? "linear" : "fast";
}

function showSelection() {
  if (!selected || !rows[selected.row] || !rows[selected.row][selected.index]) selected = null;
  $("selName").textContent = selected ? `row ${selected.row}, point ${selected.index}` : "(click a point)";
  const p = selected ? rows[selected.row][selected.index] : null;
  ["px", "py", "pz"].forEach((id, a) => ($(id).value = p ? String(p[a]) : ""));
}

// Shows a state; `job` (a move) gets its mouse-to-frame latency recorded.
function applyState(st, job) {
  const t0 = performance.now();
  const first = !state;
  state = st;
  if (st.rows) { rows = st.rows; dev = st.point_deviation; params = { u: st.u, v: st.v }; }
  if (first) { frameCamera(); $("input").textContent = st.input; fillFormats(); }
  buildSurface(st.final);
  if (st.rows || (job && job.phase !== "drag")) buildPoints();
  updateMarkers();
  showReport();
  if (st.rows) { showOptions(); showSelection(); }
  hook.state = st;
  hook.applyMs = performance.now() - t0;
  needsRender = true;
  if (job && job.t !== undefined)
    frameWaiters.push((now, start, drawn) => hook.latencies.push({ t: job.t, ms: now - job.t, final: st.final,
      phase: job.phase, wait: job.sent - job.t, request: job.received - job.sent, server: 1000 * st.report.seconds,
      apply: now - job.received, slot: t0 - job.received, js: start - t0, draw: drawn - start, show: now - drawn }));
}

function message(text, good = false) {
  $("message").textContent = text || "";
  $("message").className = good ? "message good" : "message";
}

// ---- moves: one request in flight, the newest position waits, stale ones are dropped ------
let inFlight = false, pending = null, seq = 0, restTimer = null, drag = null;

function queueMove(job) { pending = job; pump(); }
async function pump() {
  if (inFlight || !pending) return;
  const job = pending; pending = null; inFlight = true;
  job.sent = performance.now();
  let st = null;
  try {
    st = await api.edit({ op: "move", row: job.row, index: job.index, to: job.to,
      phase: job.phase, seq: ++seq }, job.phase !== "drag");
    job.received = performance.now();
    message("");
  } catch (e) {
    message(e.message);
    if (job.phase !== "drag") refresh();
  }
  inFlight = false;
  needsRender = true;
  // The newest position goes out at once, while this answer is drawn.
  if (pending) pump();
  if (st && !st.skipped) {
    if (job.phase === "drag") {  // drawn now, or when the frame before is done, if still the newest
      incoming = { st, job };
      frame();
    }
    else applyState(st, job);
  }
  if (!inFlight && !pending && drag && job.phase === "drag") {
    clearTimeout(restTimer);
    restTimer = setTimeout(() => {  // the hand rests: the full search, a fine tessellation
      if (drag && !pending) queueMove({ ...drag.last, phase: "rest" });
    }, hook.restMs);
  }
}

async function refresh() { applyState(await api.getState(true)); }

async function run(p) {  // any other request: the state it returns is shown
  try { applyState(await p); message(""); } catch (e) { message(e.message); }
}

// ---- picking and dragging ----------------------------------------------------------------
const ndc = (e) => {
  const r = renderer.domElement.getBoundingClientRect();
  return new THREE.Vector2(((e.clientX - r.left) / r.width) * 2 - 1, -((e.clientY - r.top) / r.height) * 2 + 1);
};
function screenOf(p) {
  const v = new THREE.Vector3(p[0] - centre[0], p[1] - centre[1], p[2] - centre[2]).project(camera);
  const r = renderer.domElement.getBoundingClientRect();
  return { x: r.left + ((v.x + 1) / 2) * r.width, y: r.top + ((1 - v.y) / 2) * r.height, z: v.z };
}
function pick(e) {
  let best = null, bestD = 12;
  rows.forEach((r, j) => r.forEach((p, i) => {
    const s = screenOf(p);
    if (s.z < -1 || s.z > 1) return;
    const d = Math.hypot(s.x - e.clientX, s.y - e.clientY);
    if (d < bestD) { bestD = d; best = { row: j, index: i }; }
  }));
  return best;
}
function dragTarget(e) {
  const ray = new THREE.Raycaster();
  ray.setFromCamera(ndc(e), camera);
  const o = drag.start;
  const axis = $("axis").value;
  if (axis === "view") {
    const n = new THREE.Vector3();
    camera.getWorldDirection(n);
    const plane = new THREE.Plane().setFromNormalAndCoplanarPoint(n, o);
    const hit = new THREE.Vector3();
    if (!ray.ray.intersectPlane(plane, hit)) return null;
    return [hit.x + centre[0], hit.y + centre[1], hit.z + centre[2]];
  }
  const a = new THREE.Vector3(axis === "x" ? 1 : 0, axis === "y" ? 1 : 0, axis === "z" ? 1 : 0);
  // The point of the axis line through `o` nearest to the ray.
  const w0 = o.clone().sub(ray.ray.origin), d = ray.ray.direction;
  const b = a.dot(d), dd = a.dot(w0), e2 = d.dot(w0), den = 1 - b * b;
  if (Math.abs(den) < 1e-9) return null;
  const s = (b * e2 - dd) / den;
  const q = o.clone().addScaledVector(a, s);
  return [q.x + centre[0], q.y + centre[1], q.z + centre[2]];
}

renderer.domElement.addEventListener("pointerdown", (e) => {
  if (e.button !== 0 || !state) return;
  const hit = pick(e);
  if (!hit) return;
  selected = hit;
  showSelection();
  updateMarkers();
  needsRender = true;
  const p = rows[hit.row][hit.index];
  drag = { ...hit, start: new THREE.Vector3(p[0] - centre[0], p[1] - centre[1], p[2] - centre[2]), last: null };
  controls.enabled = false;
  coarseImage(true);
  renderer.domElement.setPointerCapture(e.pointerId);
  e.preventDefault();
});
// pointerrawupdate where the browser has it: Chromium delivers pointermove only with the next
// animation frame, the raw event as soon as the hand moves.
const moveEvent = "onpointerrawupdate" in window ? "pointerrawupdate" : "pointermove";
renderer.domElement.addEventListener(moveEvent, (e) => {
  if (!drag) return;
  const to = dragTarget(e);
  if (!to) return;
  rows[drag.row][drag.index] = to;  // the point follows the hand at once
  moveDrawnPoint(drag.row, drag.index, to);
  drag.last = { row: drag.row, index: drag.index, to };
  hook.moves.push(e.timeStamp);
  clearTimeout(restTimer);
  queueMove({ ...drag.last, phase: "drag", t: e.timeStamp });
  updateMarkers();
  // Drawn with the refit of this step (or a newer one), whose answer comes next: a frame of
  // the moved point alone would only delay that one on a software rasteriser.
  if (!inFlight) needsRender = true;
});
function endDrag(e) {
  if (!drag) return;
  const d = drag;
  drag = null;
  controls.enabled = true;
  coarseImage(false);
  clearTimeout(restTimer);
  if (d.last) queueMove({ ...d.last, phase: "end", t: e.timeStamp });
}
renderer.domElement.addEventListener("pointerup", endDrag);
renderer.domElement.addEventListener("pointercancel", endDrag);

// ---- the panel ---------------------------------------------------------------------------
function fillFormats() {
  $("format").innerHTML = state.exports.map((f) => `<option>${f}</option>`).join("");
  $("format").value = state.exports.includes("step") ? "step" : "json";
}
$("mode").addEventListener("change", () => { if (state) { buildSurface(state.final); needsRender = true; } });
$("net").addEventListener("change", () => { if (state) { buildNet(); needsRender = true; } });
$("points").addEventListener("change", () => {
  for (const o of [pointsObj, rowLines]) if (o) o.visible = $("points").checked;
  needsRender = true;
});

// Options: the newest change wins while a refit runs.
let optInFlight = false, optPending = null;
async function sendOptions(o) {
  optPending = o;
  if (optInFlight) return;
  while (optPending) {
    const next = optPending; optPending = null; optInFlight = true;
    try { applyState(await api.setOptions(next)); message(""); } catch (e) { message(e.message); }
    optInFlight = false;
  }
}
// The T slider is live; one movement of it is one undo step.
const tolOf = () => diagonal * Math.pow(10, Number($("tol").value));
$("tol").addEventListener("input", () => {
  $("tolText").textContent = g4(tolOf());
  sendOptions({ tolerance: tolOf(), phase: "drag" });
});
$("tol").addEventListener("change", () => sendOptions({ tolerance: tolOf(), phase: "end" }));
$("degU").addEventListener("change", () => sendOptions({ degree: [Number($("degU").value), Number($("degV").value)] }));
$("degV").addEventListener("change", () => sendOptions({ degree: [Number($("degU").value), Number($("degV").value)] }));
for (const id of ["closedU", "closedV"])
  $(id).addEventListener("change", () => sendOptions({ closed: [$("closedU").checked, $("closedV").checked] }));
$("params").addEventListener("change", () => sendOptions({ parameters: $("params").value }));
$("search").addEventListener("change", () => sendOptions({ search: $("search").value }));

$("setPoint").addEventListener("click", () => {
  if (!selected) return message("select a point first");
  const to = ["px", "py", "pz"].map((id) => Number($(id).value));
  if (!to.every(Number.isFinite)) return message("coordinates must be numbers");
  run(api.edit({ op: "move", row: selected.row, index: selected.index, to }));
});
$("addPoint").addEventListener("click", () => {
  if (!selected) return message("select a point first");
  const r = rows[selected.row], i = selected.index;
  const a = r[i], b = r[i + 1] || r[i - 1] || a.map((x) => x + diagonal / 100);
  const p = a.map((x, k) => (r[i + 1] ? (x + b[k]) / 2 : 2 * x - b[k]));
  run(api.edit({ op: "insert", row: selected.row, index: i + 1, point: p }));
});
$("delPoint").addEventListener("click", () => {
  if (!selected) return message("select a point first");
  run(api.edit({ op: "delete", row: selected.row, index: selected.index }));
});
$("addRow").addEventListener("click", () => {
  if (!selected) return message("select a point of the row first");
  const j = selected.row, r = rows[j], nx = rows[j + 1];
  const pts = nx && nx.length === r.length ? r.map((p, i) => p.map((x, a) => (x + nx[i][a]) / 2))
    : r.map((p) => [p[0], p[1], p[2] + diagonal / 50]);
  run(api.edit({ op: "insert_row", row: j + 1, points: pts }));
});
$("delRow").addEventListener("click", () => {
  if (!selected) return message("select a point of the row first");
  run(api.edit({ op: "delete_row", row: selected.row }));
});
$("undo").addEventListener("click", () => run(api.undo()));
$("redo").addEventListener("click", () => run(api.redo()));
window.addEventListener("keydown", (e) => {
  if (e.target instanceof HTMLInputElement && e.target.type !== "checkbox" && e.target.type !== "range") return;
  const k = e.key.toLowerCase();
  if ((e.ctrlKey || e.metaKey) && k === "z") { e.preventDefault(); run(e.shiftKey ? api.redo() : api.undo()); }
  else if ((e.ctrlKey || e.metaKey) && k === "y") { e.preventDefault(); run(api.redo()); }
});
$("save").addEventListener("click", async () => {
  try { const r = await api.save(); message(`saved ${r.saved}` + (r.backup ? ` (original kept as ${r.backup})` : ""), true); }
  catch (e) { message(e.message); }
});
$("download").addEventListener("click", () => { location.href = api.downloadUrl($("format").value); });
$("exportBeside").addEventListener("click", async () => {
  try { const r = await api.exportBeside($("format").value); message(`wrote ${r.path}`, true); }
  catch (e) { message(e.message); }
});

// ---- for tests and benchmarks ------------------------------------------------------------
hook.screenOf = (row, index) => screenOf(rows[row][index]);
hook.nextFrame = () => new Promise((res) => { frameWaiters.push(res); needsRender = true; });

resize();
requestAnimationFrame(loop);
// Nothing sent, in flight or waiting to be drawn, and the last frame drawn.
Object.defineProperty(hook, "idle", {
  get: () => hook.ready && !inFlight && !pending && !drag && !incoming && !optInFlight && !needsRender && !drawing });
// The controls' limits and choices: the library's option table (GET /api/options-table).
async function applyOptionsTable() {
  const table = await api.getOptionsTable();
  const spec = (name) => table.find((o) => o.name === name);
  for (const id of ["degU", "degV"]) {
    $(id).min = spec("degree").min;
    $(id).max = spec("degree").max;
  }
  for (const [id, name] of [["params", "parameters"], ["search", "search"]]) {
    const keep = $(id).value;
    $(id).replaceChildren(...spec(name).choices.filter((c) => c !== "known").map((c) => {
      const o = document.createElement("option");
      o.textContent = c;
      return o;
    }));
    if (keep) $(id).value = keep;
  }
}
Promise.all([applyOptionsTable(), refresh()]).then(() => { hook.ready = true; }, (e) => {
  $("status").className = "status bad";
  $("status").textContent = "cannot reach the server: " + e.message;
});
