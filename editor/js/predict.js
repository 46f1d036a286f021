// The drag's prediction (docs/editor-latency.md). With the counts, knots and parameters of
// the full fit frozen for the drag (the quick refit, include/sfit/frozen_refit.h), the quick refit
// is least squares at fixed counts, knots and parameters: a linear map of the data. Moving
// point k by d moves every control point by g_k d, where g_k is the fit of data that are zero but
// for 1 at point k. When a point is selected the page asks the server for g_k and for S0, the
// quick refit of the rows as they are (POST /api/influence); while that point is dragged it draws
// S0 + g_k d at every pointer move itself, with no request on the critical path. The moves
// still go to the server (latest wins); each answer is compared with the prediction of the
// same move (it must agree within 1e-9 of the control points' size: the prediction IS the
// refit) and replaces the page's state; where it does not agree, the prediction stops for the
// drag and the answers are drawn. The server's quick refit of a drag is least squares at the
// counts, knots and parameters of the full fit frozen at the drag's start, whatever made it, so
// it is linear but where the frozen refit cannot be made (the server says why: weighted rows,
// rows the fit reordered, too many control points); the drag then waits for its answers.
import { S, hook } from "./store.js";
import * as api from "./api.js";
import { doubles } from "./pack.js";

let known = null;  // the last influence: {row, index, version, linear, why, p0, base, g, header, nu, nv}
let asking = null;  // "row:index:version" of the request under way
let onArrival = null;  // a drag waiting for its influence

const keyOf = (row, index, version) => `${row}:${index}:${version}`;

/// Asks for the influence of the selected point (if the page does not have it for the
/// current state); nothing while a drag or another request for it is under way.
export function prefetch() {
  const sel = S.selected;
  if (!sel || !S.state || S.drag || S.state.dragging) return;
  const key = keyOf(sel.row, sel.index, S.state.version);
  if ((known && known.key === key) || asking === key) return;
  asking = key;
  const t0 = performance.now();
  api.influence(sel.row, sel.index).then((j) => {
    if (asking === key) asking = null;
    const k = { key: keyOf(j.row, j.index, j.version), row: j.row, index: j.index, version: j.version,
      linear: j.linear, why: j.why || "" };
    if (j.linear) {
      const { control_points_f64: cp, control_points_shape: shape, ...header } = j.surface;
      Object.assign(k, { p0: j.point, base: doubles(cp), g: doubles(j.influence), nu: shape[0], nv: shape[1], header });
    }
    known = k;
    hook.influence = { row: k.row, index: k.index, version: k.version, linear: k.linear, why: k.why,
      seconds: j.seconds, frozenSeconds: j.frozen_seconds, ms: performance.now() - t0 };
    if (hook.pressT !== undefined && !hook.influenceTimes) hook.influenceTimes = { asked: hook.pressT - t0, got: performance.now() - hook.pressT };
    if (onArrival) onArrival(k);
    settle();
  }, () => { if (asking === key) asking = null; settle(); });
}

/// The prediction for a drag of point (row, index) that started at state `version`: calls
/// `use(influence)` now (true) or when it arrives (false), if it is linear and of that state.
export function forDrag(row, index, version, use) {
  const fits = (k) => k.linear && k.row === row && k.index === index && k.version === version;
  onArrival = null;
  if (known && fits(known)) { use(known); return true; }
  onArrival = (k) => { if (fits(k)) { onArrival = null; use(k); } };
  prefetch();
  return false;
}
export function dropDrag() { onArrival = null; }
/// True while an influence asked for has not arrived; `then` runs when it does (or fails).
export const asked = () => asking !== null;
let settled = [];
export function whenSettled(then) { settled.push(then); }
function settle() { const fs = settled; settled = []; for (const f of fs) f(); }

/// The control points S0 + g (to - p0) as the surface contract (nested control_points).
export function predicted(k, to) {
  const d = [to[0] - k.p0[0], to[1] - k.p0[1], to[2] - k.p0[2]];
  const cp = new Array(k.nu);
  for (let i = 0, m = 0; i < k.nu; i++) {
    const row = cp[i] = new Array(k.nv);
    for (let j = 0; j < k.nv; j++, m++) {
      const g = k.g[m], b = 3 * m;
      row[j] = [k.base[b] + g * d[0], k.base[b + 1] + g * d[1], k.base[b + 2] + g * d[2]];
    }
  }
  return { ...k.header, control_points: cp };
}

/// How far the server's control points `surface` are from the prediction of the same move:
/// the largest difference over the largest coordinate (Infinity where the shapes differ).
export function mismatch(k, to, surface) {
  const p = predicted(k, to).control_points, q = surface.control_points;
  if (q.length !== p.length || q[0].length !== p[0].length) return Infinity;
  let big = 0, off = 0;
  for (let i = 0; i < q.length; i++)
    for (let j = 0; j < q[i].length; j++)
      for (let a = 0; a < 3; a++) {
        big = Math.max(big, Math.abs(q[i][j][a]));
        off = Math.max(off, Math.abs(q[i][j][a] - p[i][j][a]));
      }
  return off / Math.max(big, Number.MIN_VALUE);
}
