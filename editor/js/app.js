// The editor page: the rows and the surface in a three.js view; edits go to the server's
// JSON API (docs/editor-api.md), which refits through IncrementalFit. This module shows the
// states the server answers and sends the moves; view.js draws, draw.js builds what is
// drawn, drag.js picks and drags, panel.js is the panel, legend.js the colour legends.
import { $, S, hook } from "./store.js";
import * as view from "./view.js";
import { buildSurface, buildPoints, updateMarkers, constraintShown, dragDetail, warmUp } from "./draw.js";
import * as panel from "./panel.js";
import * as drag from "./drag.js";
import * as api from "./api.js";
import * as predict from "./predict.js";

// ---- showing a state ---------------------------------------------------------------------
let lastFinal = null;  // counts and rule of the last final surface shown: before -> after
function countsOf(st) { return `${st.report.control_points[0]} × ${st.report.control_points[1]}`; }

// Shows a state; `job` (a move) gets its mouse-to-frame latency recorded.
function applyState(st, job) {
  const t0 = performance.now();
  const first = !S.state;
  S.state = st;
  if (st.rows) { S.rows = st.rows; S.dev = st.point_deviation; S.params = { u: st.u, v: st.v, vp: st.v_points || null }; }
  if (first) {
    view.fitView(true);
    $("input").textContent = st.input;
    panel.fillFormats();
    $("step").value = String(Number((S.diagonal / 1000).toPrecision(2)));
  }
  if (st.rows) {  // the rows look closed and are fitted open: closed u in one click
    $("closedHint").style.display = st.closed_hint ? "block" : "none";
    $("closedHintText").textContent = st.closed_hint || "";
  }
  if (st.rows) panel.showSelection();  // before the markers: a deleted row's selection goes
  buildSurface(st.final);
  if (st.rows || (job && job.phase !== "drag")) buildPoints();
  S.overCount = updateMarkers(!!st.rows);
  panel.showReport();
  if (st.rows) panel.showOptions();
  if (st.final && !st.dragging && st.rows) showCountChange(st);
  hook.state = st;
  hook.shown.push({ version: st.version, final: st.final, t: performance.now() });
  hook.applyMs = performance.now() - t0;
  view.redraw();
  if (job && job.t !== undefined)
    view.onFrameShown((now, start, drawn) => hook.latencies.push({ t: job.t, ms: now - job.t, final: st.final,
      phase: job.phase, wait: job.sent - job.t, request: job.received - job.sent, server: 1000 * st.report.seconds,
      apply: now - job.received, slot: t0 - job.received, js: start - t0, draw: drawn - start, show: now - drawn }));
  if (st.rows && !st.dragging) predict.prefetch();  // the selected point's influence for its next drag
}

// ---- the drag's prediction (predict.js): S0 + g d drawn at the pointer move itself ---------
// `job` {to, t}: drawn when the frame before is done; a newer move supersedes it (latest wins).
// The state drawn is the last answer's with the predicted control points.
const NEWEST = { version: Number.MAX_SAFE_INTEGER };
function showPrediction(job) {
  view.showWhenFree(NEWEST, job, applyPrediction);
}
function applyPrediction(_, job) {
  const t0 = performance.now();
  const d = S.drag;
  if (!d || !d.pred) return;
  S.state = { ...S.state, surface: predict.predicted(d.pred, job.to), final: false, dragging: true };
  buildSurface(false);
  hook.shown.push({ version: S.state.version, final: false, predicted: true, t: performance.now() });
  view.redraw();
  view.onFrameShown((now, start, drawn) => hook.latencies.push({ t: job.t, ms: now - job.t, final: false,
    phase: "drag", predicted: true, wait: 0, request: 0, server: 0, apply: now - t0, slot: t0 - job.t,
    js: start - t0, draw: drawn - start, show: now - drawn }));
}
// A drag step's answer to a predicted move: compared with the prediction of the same move.
// Where they agree it replaces the page's state (report, version) without drawing again: the
// surface drawn is that prediction or a newer one's. Where they do not, the prediction stops
// for this drag and the answer is drawn.
function answerPredicted(st, job) {
  const off = predict.mismatch(job.pk, job.to, st.surface);
  hook.predictionChecks.push({ seq: job.seq, off });
  const d = S.drag;
  if (off <= 1e-9 && d && d.pred === job.pk) {
    S.state = { ...st, surface: S.state.surface };
    hook.state = S.state;
    panel.showReport();
    return;
  }
  if (d && d.pred === job.pk) d.pred = null;
  view.showWhenFree(st, job, applyState);
}

// Calm sculpting: the count change of a final surface is shown (before -> after); with the
// hold on, the full search's answer for the current rows is shown beside the held surface.
let searchSeq = 0, searching = false;
async function showCountChange(st) {
  const now = { counts: countsOf(st), rule: st.report.parameters };
  const before = lastFinal;
  lastFinal = now;
  if (!before) return;
  const el = $("counts");
  if (st.options.hold) {
    const mine = ++searchSeq;
    el.textContent = `held at ${now.counts} (${now.rule}); searching for the fewest…`;
    try {
      searching = true;
      const r = await api.search({ parameters: S.ruleBeforeHold || "auto" }).finally(() => { searching = false; });
      if (mine !== searchSeq) return;
      if (r.cancelled) {  // a drag made it stale; the drag's final surface searches again
        hook.dropped.push({ phase: "search" });
        el.textContent = `held at ${now.counts} (${now.rule}); the search was dropped (you moved the point)`;
        return;
      }
      el.textContent = `held at ${now.counts} (${now.rule}); the full search now gives ${r.counts[0]} × ${r.counts[1]} ` +
        `(${r.parameters}${r.within ? "" : ", not within T"}): release the hold to take it`;
      hook.search = r;
    } catch (e) { el.textContent = `held at ${now.counts}; the search failed: ${e.message}`; }
  } else if (before.counts !== now.counts || before.rule !== now.rule) {
    el.textContent = `control points ${before.counts} -> ${now.counts}` +
      (before.rule !== now.rule ? `, parameters ${before.rule} -> ${now.rule}` : "") +
      " (hold the shape to keep them while sculpting)";
  }
}

// ---- moves: one request in flight, the newest position waits, stale ones are dropped ------
let inFlight = false, pending = null, seq = 0, restTimer = null, current = null;

// A drag step while a full search runs that it makes stale (the rest's, the hold's search):
// the server drops that search (POST /api/cancel) rather than finish it and then replace it.
function dropStaleSearch() {
  if ((current && current.phase === "rest" && !current.cancelSent) || searching) {
    if (current && current.phase === "rest") current.cancelSent = true;
    api.cancel().catch(() => {});
  }
}
function queueMove(job) {
  pending = job;
  if (job.phase === "drag") dropStaleSearch();
  pump();
}
// A predicted drag step (its frame already drawn by the page) goes out at most every
// PREDICTED_GAP ms, the newest position then: the server's answers only replace the readout
// (deviation, T used), and a request less in flight leaves the two cores to the drawing.
const PREDICTED_GAP = 100;
let lastSent = -Infinity, gapTimer = null;
async function pump() {
  if (inFlight || !pending) return;
  // A drag's first steps wait for the influence asked for (the prediction draws them when it
  // comes): a step the server took first would make it "a drag under way", not linear.
  const d = S.drag;
  if (pending.phase === "drag" && !pending.pk && d && !d.pred && predict.asked()) {
    predict.whenSettled(pump);
    return;
  }
  if (pending.phase === "drag" && !pending.pk && d && d.pred && d.row === pending.row && d.index === pending.index)
    pending.pk = d.pred;  // queued before the prediction began: checked against it too
  if (pending.pk && pending.phase === "drag" && performance.now() - lastSent < PREDICTED_GAP) {
    if (!gapTimer) gapTimer = setTimeout(() => { gapTimer = null; pump(); }, PREDICTED_GAP - (performance.now() - lastSent));
    return;
  }
  const job = pending; pending = null; inFlight = true; current = job;
  lastSent = performance.now();
  job.sent = performance.now();
  let st = null;
  try {
    // seq from the wall clock (microseconds), so it grows across pages too: a page opened
    // after another has dragged is not taken for stale steps by the server.
    seq = Math.max(seq + 1, Math.floor((performance.timeOrigin + performance.now()) * 1000));
    job.seq = seq;
    st = await api.edit({ op: "move", row: job.row, index: job.index, to: job.to,
      phase: job.phase, seq }, job.phase !== "drag", !!job.pk);
    job.received = performance.now();
    if (st.cancelled) hook.dropped.push({ phase: job.phase, version: st.version });
  } catch (e) {
    panel.message(e.message);
    if (job.phase !== "drag") refresh();
  }
  inFlight = false; current = null;
  if (!job.pk) view.redraw();  // a predicted step's frame is the prediction's
  // The newest position goes out at once, while this answer is drawn.
  if (pending) pump();
  if (st && !st.skipped) {
    if (job.phase === "drag" && job.pk) answerPredicted(st, job);
    else if (job.phase === "drag" && S.drag && S.drag.pred) {  // sent before the prediction began: older
      S.state = { ...st, surface: S.state.surface };
      hook.state = S.state;
      panel.showReport();
    }
    else if (job.phase === "drag") view.showWhenFree(st, job, applyState);  // drawn now, or when the frame before is done
    else applyState(st, job);
  }
  if (!inFlight && !pending && S.drag && job.phase === "drag") {
    clearTimeout(restTimer);
    restTimer = setTimeout(() => {  // the hand rests: the full search, a fine tessellation
      if (S.drag && S.drag.last && !pending) {
        dragDetail(null);  // every row drawn again while the hand rests
        queueMove({ ...S.drag.last, phase: "rest" });
      }
    }, hook.restMs);
  }
}

// The progress of a full search under way (phase, pairs tried, best so far), polled while a
// request that may run one is out.
let progressBusy = false;
setInterval(async () => {
  const el = $("progress");
  if (!api.fullInFlight() || progressBusy) { if (!api.fullInFlight()) el.style.display = "none"; return; }
  progressBusy = true;
  try {
    const p = await api.progress();
    if (p.running && api.fullInFlight()) {
      el.textContent = `full search: ${p.phase}${p.total ? ` ${p.done}/${p.total}` : ""}, ${p.pairs_tried} pairs tried` +
        (p.best ? `, best so far ${p.best[0]} × ${p.best[1]}` : "") + `, ${p.seconds.toFixed(1)} s`;
      el.style.display = "block";
      hook.progress.push(p);
    }
  } catch (_) { /* the next request says what is wrong */ }
  progressBusy = false;
}, 150);

async function refresh() { applyState(await api.getState(true)); }

// Any other request: the state it returns is shown; `then` runs first (e.g. the selection).
async function run(p, then) {
  try {
    const st = await p;
    if (then) { S.rows = st.rows || S.rows; then(st); }
    applyState(st);
    panel.message("");
  } catch (e) { panel.message(e.message); }
}

Object.assign(S.fns, {
  applyState, queueMove, showPrediction, dropStaleSearch, run,
  coarseSurface: () => { buildSurface(false); view.redraw(); }, refresh, message: panel.message, showCoords: panel.showCoordsSoon,
  showSelection: panel.showSelection, checkNear: panel.checkNear, step: panel.step,
  moveInFlight: () => inFlight, readOnlyEdits: () => false,
});

// ---- for tests and benchmarks ------------------------------------------------------------
hook.screenOf = (row, index) => view.screenOf(S.rows[row][index]);
hook.movesSettled = () => !inFlight && !pending;  // every move sent and answered (a drag may go on)
hook.surfaceShown = () => S.state.surface.control_points;
hook.nextFrame = () => new Promise((res) => { view.onFrameShown(res); view.redraw(); });
hook.rows = () => S.rows;
hook.selected = () => S.selected;
hook.pick = drag.pick;
hook.refresh = refresh;
hook.viewFrom = (dir) => view.fitView(false, dir);  // the whole data seen from direction `dir`
hook.constraint = constraintShown;
hook.screenOfPoint = (p) => view.screenOf(p);

view.start();
// Nothing sent, in flight or waiting to be drawn, and the last frame drawn.
Object.defineProperty(hook, "idle", {
  get: () => hook.ready && !inFlight && !pending && !S.drag && !drag.nudging() && !view.busy() &&
    !panel.optionsBusy() && !view.renderPending() });
// With the shape held, the full search shown after a final surface is under way.
Object.defineProperty(hook, "searching", { get: () => searching });
// Another client (a second page, a script) or the server (a drag whose page went away) may
// change the session: while idle, the page asks for the version now and then and catches up.
setInterval(async () => {
  if (!hook.idle || S.drag) return;
  try {
    const st = await api.getState(false);
    if (hook.idle && !S.drag && S.state && st.version !== S.state.version) await refresh();
  } catch (_) { /* the server is gone: the next edit says so */ }
}, 2000);
// The controls' limits and choices: the library's option table (GET /api/options-table).
async function applyOptionsTable() {
  const table = await api.getOptionsTable();
  const spec = (name) => table.find((o) => o.name === name);
  for (const id of ["degU", "degV"]) {
    $(id).min = spec("degree").min;
    $(id).max = spec("degree").max;
  }
  for (const [id, name] of [["params", "parameters"], ["search", "search"], ["knots", "knots"]]) {
    const keep = $(id).value;
    $(id).replaceChildren(...spec(name).choices.filter((c) => c !== "known").map((c) => {
      const o = document.createElement("option");
      o.textContent = c;
      return o;
    }));
    if (keep) $(id).value = keep;
  }
}
Promise.all([applyOptionsTable(), refresh()]).then(() => { warmUp(view.renderer, view.scene, view.camera); hook.ready = true; }, (e) => {
  $("status").className = "status bad";
  $("status").textContent = "cannot reach the server: " + e.message;
});
