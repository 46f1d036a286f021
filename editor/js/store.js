// The page's shared state: what the server last said and what the page shows. Modules read
// and write it; the functions other modules need at run time (applyState, queueMove, ...)
// are registered here by their owners, so no module imports its user.
export const $ = (id) => document.getElementById(id);

// For tests and benchmarks: the last state, frames drawn, move-to-frame latencies, the
// times of the drag's mouse events; restMs: how long the hand rests before the full fit.
// progress: the full searches' progress seen; dropped: the searches a drag made stale;
// shown: every state drawn (version, final, time); predictionChecks: each predicted drag
// step's answer against its prediction (seq, off: the difference over the control points'
// size); influence: the last influence asked for (predict.js).
export const hook = (window.sfitEditor = { state: null, frames: 0, latencies: [], moves: [], ready: false, restMs: 250,
  progress: [], dropped: [], shown: [], predictionChecks: [], influence: null });

export const S = {
  state: null,      // the last state from the server
  rows: [],         // [[x, y, z], ...] per row, as the page shows them
  dev: [],          // per point fraction of T used
  params: null,     // {u: per row, v, vp: per row where each point has its own v}
  centre: [0, 0, 0],
  diagonal: 1,
  selected: null,   // {row, index}
  fns: {},          // applyState, queueMove, refresh, run, message, ... (registered by owners)
};

export const g4 = (x) => (Math.abs(x) >= 1e4 || (Math.abs(x) < 1e-3 && x !== 0) ? x.toExponential(3) : x.toPrecision(4));
export const vec = (p) => `${g4(p[0])}, ${g4(p[1])}, ${g4(p[2])}`;
export const setText = (el, text) => { if (el.textContent !== text) el.textContent = text; };
export const setClass = (el, name) => { if (el.className !== name) el.className = name; };

export function boxOf(rs) {
  const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
  for (const r of rs) for (const p of r) for (let a = 0; a < 3; a++) {
    lo[a] = Math.min(lo[a], p[a]); hi[a] = Math.max(hi[a], p[a]);
  }
  return { lo, hi };
}
