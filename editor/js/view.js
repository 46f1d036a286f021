// The three.js view: renderer, camera, orbit/pan/zoom-to-cursor, fit view, and the frame loop
// (frames drawn on demand, one at a time, the newest refitted drag state first).
import * as THREE from "three";
import { OrbitControls } from "three/addons/controls/OrbitControls.js";
import { $, S, hook, boxOf } from "./store.js";

export const viewEl = $("view");
// On a software rasteriser (SwiftShader, llvmpipe) multisampling costs most of each frame.
function softwareGL() {
  const gl = document.createElement("canvas").getContext("webgl2");
  const info = gl && gl.getExtension("WEBGL_debug_renderer_info");
  const name = info ? String(gl.getParameter(info.UNMASKED_RENDERER_WEBGL)) : "";
  if (gl) gl.getExtension("WEBGL_lose_context")?.loseContext();
  return /swiftshader|llvmpipe|software/i.test(name);
}
hook.softwareGL = softwareGL();
export const renderer = new THREE.WebGLRenderer({ antialias: !hook.softwareGL, preserveDrawingBuffer: true });
renderer.setPixelRatio(window.devicePixelRatio || 1);
viewEl.appendChild(renderer.domElement);
export const canvas = renderer.domElement;
export const scene = new THREE.Scene();
scene.background = new THREE.Color(0x1d2024);
export const camera = new THREE.PerspectiveCamera(40, 1, 0.001, 1000);
export const controls = new OrbitControls(camera, canvas);
controls.zoomToCursor = true;       // the wheel zooms towards the point under the cursor
controls.screenSpacePanning = true;
scene.add(new THREE.HemisphereLight(0xffffff, 0x404050, 1.6));
const sun = new THREE.DirectionalLight(0xffffff, 1.4);
scene.add(sun);
export const world = new THREE.Group();  // data coordinates less `S.centre`
scene.add(world);

let needsRender = true;
let frameWaiters = [];
export const redraw = () => { needsRender = true; };
export const renderPending = () => needsRender;
controls.addEventListener("change", redraw);

// On software GL the pixels dominate a frame: while a point is dragged the view is drawn at
// half resolution (the quick image), at full resolution again when the hand lets go.
export function coarseImage(on) {
  if (!hook.softwareGL) return;
  renderer.setPixelRatio((window.devicePixelRatio || 1) * (on ? 0.5 : 1));
  resize();
}
let box = null;  // the canvas's box on the page (canvasBox())
export function resize() {
  box = null;
  const w = viewEl.clientWidth, h = viewEl.clientHeight;
  renderer.setSize(w, h);
  camera.aspect = w / Math.max(1, h);
  camera.updateProjectionMatrix();
  needsRender = true;
}
window.addEventListener("resize", resize);

// Frames the data: on the first state from a fixed direction, afterwards ("F") from the
// current direction; the whole box in view, whatever the user did to the camera.
export function fitView(first, from) {
  const { lo, hi } = boxOf(S.rows);
  if (first) {
    S.centre = [0, 1, 2].map((a) => (lo[a] + hi[a]) / 2);
    S.diagonal = Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]) || 1;
  }
  const diag = Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]) || S.diagonal;
  const target = new THREE.Vector3(...[0, 1, 2].map((a) => (lo[a] + hi[a]) / 2 - S.centre[a]));
  const dir = from ? new THREE.Vector3(...from).normalize() : first || !Number.isFinite(camera.position.x)
    ? new THREE.Vector3(0.7, -0.85, 0.65).normalize()
    : camera.position.clone().sub(controls.target).normalize();
  if (!(dir.lengthSq() > 0.5)) dir.set(0.7, -0.85, 0.65).normalize();
  const dist = 1.15 * diag / 2 / Math.tan((camera.fov * Math.PI) / 360) / Math.min(1, camera.aspect);
  camera.near = diag / 1000; camera.far = diag * 40;
  camera.position.copy(target).addScaledVector(dir, dist);
  camera.up.set(0, 0, 1);
  controls.target.copy(target);
  camera.updateProjectionMatrix();
  controls.update();
  needsRender = true;
}

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
export const busy = () => drawing || !!incoming;
export function showWhenFree(st, job, apply) {
  incoming = { st, job, apply };
  frame();
}
function loop() {
  requestAnimationFrame(loop);
  frame();
}
export function frame() {
  if (drawing) return;
  if (incoming) {
    const { st, job, apply } = incoming;
    incoming = null;
    if (!S.state || st.version >= S.state.version) apply(st, job);
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
export function onFrameShown(f) { frameWaiters.push(f); }
export function start() { resize(); requestAnimationFrame(loop); }

// ---- screen and rays ---------------------------------------------------------------------
export const local = (p) => new THREE.Vector3(p[0] - S.centre[0], p[1] - S.centre[1], p[2] - S.centre[2]);
export const global = (v) => [v.x + S.centre[0], v.y + S.centre[1], v.z + S.centre[2]];
// The canvas's box on the page, kept until it is resized or the page scrolled: reading it
// forces a layout of the page (the panel changed by the last answer) at every mouse event.
const canvasBox = () => box || (box = canvas.getBoundingClientRect());
window.addEventListener("scroll", () => { box = null; }, true);
export function screenOf(p) {
  const v = local(p).project(camera);
  const r = canvasBox();
  return { x: r.left + ((v.x + 1) / 2) * r.width, y: r.top + ((1 - v.y) / 2) * r.height, z: v.z };
}
export function rayOf(e) {
  const r = canvasBox();
  const ndc = new THREE.Vector2(((e.clientX - r.left) / r.width) * 2 - 1, -((e.clientY - r.top) / r.height) * 2 + 1);
  const ray = new THREE.Raycaster();
  ray.setFromCamera(ndc, camera);
  return ray.ray;
}
