// The panel: report, status, fit options (T typed with units and a log-scale slider, the
// hold), the selected point's fields (refused in place when empty or not a number), the
// edit buttons, history and files, the zebra controls, messages and warnings.
import { $, S, hook, g4, vec, setText, setClass } from "./store.js";
import { redraw } from "./view.js";
import { buildSurface, buildNet, showPoints, setZebra, updateMarkers } from "./draw.js";
import * as api from "./api.js";

export function message(text, good = false) {
  setText($("message"), text || "");
  setClass($("message"), good ? "message good" : "message");
}
export function warn(text) {
  setText($("warn"), text || "");
  $("warn").style.display = text ? "block" : "none";
}

// ---- the report --------------------------------------------------------------------------
let reportCells = null;
export function showReport() {
  const st = S.state, r = st.report, d = st.deviation;
  const used = d.used === null ? "∞" : (100 * d.used).toFixed(1);
  if (!reportCells) {
    const names = ["control points", "points", "max deviation", "T", "used", "worst point", "parameters"];
    $("report").innerHTML = "<table>" + names.map((n) => `<tr><td>${n}</td><td></td></tr>`).join("") + "</table>";
    reportCells = Array.from($("report").querySelectorAll("tr td:nth-child(2)"));
  }
  const c = reportCells;
  setText(c[0], `${r.control_points[0]} × ${r.control_points[1]} (degree ${r.degree[0]} × ${r.degree[1]})` +
    (st.options.hold ? " held" : ""));
  setText(c[1], `${r.points} in ${r.rows} rows`);
  setText(c[2], vec(d.max));
  setText(c[3], vec(d.tolerance));
  setText(c[4], `${used}% of T: ${d.within ? "within T" : "NOT within T"}`);
  setClass(c[4], d.within ? "within" : "out");
  setText(c[5], `row ${r.worst.row}, point ${r.worst.index} (red)`);
  setText(c[6], `${r.parameters}; ${r.solves} solves, ${(1000 * r.seconds).toFixed(2)} ms`);
  const s = $("status");
  const held = st.options.hold ? " (counts and rule held)" : "";
  if (st.best_effort && st.final) {
    // No surface within T was found: the best one found is shown, to fix the points or T.
    setClass(s, "status bad");
    setText(s, `no surface within T found (${st.best_effort}): the best found is shown` +
      (d.within ? "; change the points, T or the degree" : `, NOT within T at ${S.overCount || "some"} points (ringed magenta, listed below)`));
  } else if (!d.within && !st.final) {
    setClass(s, "status quick over");
    setText(s, `quick refit at the current counts, every point checked: ${used}% of T, over T at the worst point; ` +
      "the final fit follows when you pause");
  } else if (!d.within) {
    setClass(s, "status bad");
    setText(s, `NOT within T at ${S.overCount || "some"} points (ringed magenta; the worst red)` + held +
      (st.options.hold ? ": release the hold, raise T or move the points" : ": raise T or move the ringed points, listed below"));
  } else if (st.final) {
    setClass(s, "status");
    setText(s, st.options.hold ? `final surface at the held counts and rule, every point checked (max ${used}% of T)`
      : `final surface: fewest control points, every point checked (max ${used}% of T)`);
  } else {
    setClass(s, "status quick");
    setText(s, `quick refit at the current counts (every point checked, max ${used}% of T); the final one follows when you pause`);
  }
  if (st.rows) showFailing();
  setText($("depths"), `${st.undo} undo, ${st.redo} redo`);
  const lock = $("lock");
  setText(lock, st.read_only ? `read-only: ${st.lock}` : st.lock || "");
  lock.style.display = st.lock ? "block" : "none";
  $("save").disabled = !!st.read_only;
  $("save").title = st.read_only ? st.lock : "";
}

// The points over T (final surface), worst first: each a button that selects the point.
const FAILING_SHOWN = 12;
function showFailing() {
  const el = $("failing");
  const over = [];
  if (S.state.final) S.dev.forEach((r, j) => r && r.forEach((x, i) => { if (x > 1) over.push({ row: j, index: i, x }); }));
  el.style.display = over.length ? "block" : "none";
  if (!over.length) return el.replaceChildren();
  over.sort((a, b) => b.x - a.x);
  const head = document.createElement("div");
  head.textContent = `${over.length} point${over.length > 1 ? "s" : ""} over T` + (over.length > FAILING_SHOWN ? ` (the ${FAILING_SHOWN} worst)` : "") + ":";
  el.replaceChildren(head, ...over.slice(0, FAILING_SHOWN).map((f) => {
    const b = document.createElement("button");
    b.className = "failpoint";
    b.dataset.row = f.row; b.dataset.index = f.index;
    b.textContent = `row ${f.row}, point ${f.index}: ${(100 * f.x).toFixed(0)}% of T`;
    b.addEventListener("click", () => { S.selected = { row: f.row, index: f.index }; showSelection(); updateMarkers(); redraw(); });
    return b;
  }));
}

// ---- units and T -------------------------------------------------------------------------
const UNIT = { mm: 1, cm: 10, m: 1000, km: 1e6, in: 25.4, ft: 304.8, um: 1e-3 };
const unitOf = () => (S.state && S.state.units) || "";
/// T typed: "0.05", "0.05 mm" (converted to the data's unit when both are lengths), "0.1%"
/// (of the data's diagonal); null if not understood.
export function parseTolerance(text) {
  const m = /^\s*([+]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?)\s*([a-zA-Z%]*)\s*$/.exec(text);
  if (!m) return null;
  const x = Number(m[1]), u = m[2].toLowerCase();
  if (!Number.isFinite(x) || x < 0) return null;
  if (u === "") return x;
  if (u === "%") return (x / 100) * S.diagonal;
  const data = unitOf();
  if (u === data) return x;
  if (UNIT[u] && UNIT[data]) return (x * UNIT[u]) / UNIT[data];
  return null;
}
function showTolerance(t) {
  $("tolIn").value = `${g4(t)}${unitOf() ? " " + unitOf() : ""}`;
  $("tolIn").classList.remove("invalid");
  $("tolRel").textContent = `${g4((100 * t) / S.diagonal)}% of the diagonal`;
}
export function showOptions() {
  const o = S.state.options;
  const t = Math.max(...o.tolerance);
  $("tol").value = t > 0 ? Math.log10(t / S.diagonal) : $("tol").min;
  if (document.activeElement !== $("tolIn")) showTolerance(t);
  $("degU").value = o.degree[0]; $("degV").value = o.degree[1];
  $("closedU").checked = o.closed[0]; $("closedV").checked = o.closed[1];
  $("params").value = o.parameters === "known" ? "auto" : o.parameters;
  $("search").value = o.search === "linear" ? "linear" : "fast";
  $("knots").value = o.knots || "uniform";
  $("hold").checked = !!o.hold;
  $("units").textContent = unitOf() || "data units";
}

// ---- the selected point ------------------------------------------------------------------
const FIELDS = ["px", "py", "pz"];
const NUMBER = /^\s*[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?\s*$/;
/// The value of a coordinate field, or null (empty or not a number: never read as 0).
export function fieldValue(id) {
  const s = $(id).value;
  return NUMBER.test(s) && Number.isFinite(Number(s)) ? Number(s) : null;
}
function markField(id) {
  const ok = fieldValue(id) !== null || !S.selected;
  $(id).classList.toggle("invalid", !ok);
  $(id).setAttribute("aria-invalid", ok ? "false" : "true");
  $(id).title = ok ? "" : ($(id).value.trim() === "" ? "empty: type a number" : "not a number");
  return ok;
}
export function showCoords(p) {
  FIELDS.forEach((id, a) => {
    $(id).value = p ? String(p[a]) : "";
    $(id).classList.remove("invalid");
    $(id).setAttribute("aria-invalid", "false");
  });
}
// While dragging, the fields follow the hand once per animation frame (not per raw pointer
// event: each write re-lays the panel out).
let coordsSoon = null;
export function showCoordsSoon(p) {
  if (!coordsSoon) requestAnimationFrame(() => { const q = coordsSoon; coordsSoon = null; if (q) showCoords(q); });
  coordsSoon = p;
}
export function showSelection() {
  const sel = S.selected;
  if (sel && !(S.rows[sel.row] && S.rows[sel.row][sel.index])) S.selected = null;
  const s = S.selected;
  $("selName").textContent = s ? `row ${s.row}, point ${s.index}` : "(click a point)";
  coordsSoon = null;
  showCoords(s ? S.rows[s.row][s.index] : null);
}
for (const id of FIELDS) {
  $(id).addEventListener("input", () => markField(id));
  $(id).addEventListener("keydown", (e) => { if (e.key === "Enter") setTyped(); });
}
function setTyped() {
  if (!S.selected) return message("select a point first");
  const bad = FIELDS.filter((id) => !markField(id));
  if (bad.length) {
    $(bad[0]).focus();
    return message(`${bad.map((id) => id[1]).join(", ")}: ${bad.length > 1 ? "are" : "is"} empty or not a number; ` +
      "type a number (nothing was changed)");
  }
  const to = FIELDS.map(fieldValue);
  const { row, index } = S.selected;
  S.fns.run(api.edit({ op: "move", row, index, to })).then(() => checkNear(row, index, to));
}
$("setPoint").addEventListener("click", setTyped);

// A point that lands on or near another (its row and the rows next to it): the fit may need
// many more control points there, or folds.
export function checkNear(row, index, p) {
  const t = S.state ? Math.max(...S.state.deviation.tolerance) : 0;
  const r = S.rows[row] || [];
  let spacing = 0;
  for (let i = 1; i < r.length; i++) spacing += Math.hypot(r[i][0] - r[i - 1][0], r[i][1] - r[i - 1][1], r[i][2] - r[i - 1][2]);
  spacing /= Math.max(1, r.length - 1);
  const near = Math.max(t, 0.05 * spacing, 1e-9 * S.diagonal);
  let found = null;
  for (const j of [row - 1, row, row + 1]) {
    const rr = S.rows[j];
    if (!rr) continue;
    rr.forEach((q, i) => {
      if (j === row && i === index) return;
      const d = Math.hypot(q[0] - p[0], q[1] - p[1], q[2] - p[2]);
      if (d <= near && (!found || d < found.d)) found = { j, i, d };
    });
  }
  if (found)
    warn(`warning: row ${row}, point ${index} ${found.d === 0 ? "lands on" : `is ${g4(found.d)} from`} row ${found.j}, point ${found.i}` +
      ` (closer than ${g4(near)}): the surface may need many more control points there or fold; move it away or delete one`);
  else warn("");
  return found;
}
hook.checkNear = (row, index) => !!checkNear(row, index, S.rows[row][index]);

export function step() {
  const s = parseTolerance($("step").value);
  return s && s > 0 ? s : S.diagonal / 1000;
}

// ---- buttons -----------------------------------------------------------------------------
export function fillFormats() {
  $("format").innerHTML = S.state.exports.map((f) => `<option>${f}</option>`).join("");
  $("format").value = S.state.exports.includes("step") ? "step" : "json";
}
$("mode").addEventListener("change", () => { if (S.state) { buildSurface(S.state.final); redraw(); } });
$("net").addEventListener("change", () => { if (S.state) { buildNet(); redraw(); } });
$("points").addEventListener("change", () => showPoints($("points").checked));
const ZDIR = { y: [0, 1, 0], x: [1, 0, 0], z: [0, 0, 1] };
function zebra() { setZebra(Number($("stripes").value), ZDIR[$("stripeDir").value] || ZDIR.y); $("stripesN").textContent = $("stripes").value; }
$("stripes").addEventListener("input", zebra);
$("stripeDir").addEventListener("change", zebra);

// Options: the newest change wins while a refit runs.
let optInFlight = false, optPending = null;
export const optionsBusy = () => optInFlight;
export async function sendOptions(o) {
  optPending = o;
  if (optInFlight) return;
  while (optPending) {
    const next = optPending; optPending = null; optInFlight = true;
    try { S.fns.applyState(await api.setOptions(next)); message(""); } catch (e) { message(e.message); }
    optInFlight = false;
  }
}
// The T slider (log scale, a fraction of the diagonal) is live; one movement is one undo step.
const tolOf = () => S.diagonal * Math.pow(10, Number($("tol").value));
$("tol").addEventListener("input", () => { showTolerance(tolOf()); sendOptions({ tolerance: tolOf(), phase: "drag" }); });
$("tol").addEventListener("change", () => sendOptions({ tolerance: tolOf(), phase: "end" }));
$("tolIn").addEventListener("change", () => {
  const t = parseTolerance($("tolIn").value);
  if (t === null) {
    $("tolIn").classList.add("invalid");
    return message(`T: '${$("tolIn").value}' is not a length (a number, with ${unitOf() || "no"} unit or %)`);
  }
  $("tolIn").classList.remove("invalid");
  if (S.state && S.state.options.tolerance.every((x) => x === t)) return;  // nothing changed
  sendOptions({ tolerance: t });
});
$("degU").addEventListener("change", () => sendOptions({ degree: [Number($("degU").value), Number($("degV").value)] }));
$("degV").addEventListener("change", () => sendOptions({ degree: [Number($("degU").value), Number($("degV").value)] }));
for (const id of ["closedU", "closedV"])
  $(id).addEventListener("change", () => sendOptions({ closed: [$("closedU").checked, $("closedV").checked] }));
$("knots").addEventListener("change", () => sendOptions({ knots: $("knots").value }));
$("params").addEventListener("change", () => { S.ruleBeforeHold = $("params").value; sendOptions({ parameters: $("params").value }); });
$("search").addEventListener("change", () => sendOptions({ search: $("search").value }));
// The hold: counts and rule kept (released: the rule chosen before, and the search again).
$("hold").addEventListener("change", () => {
  if ($("hold").checked) {
    S.ruleBeforeHold = S.state.options.parameters;
    sendOptions({ hold: true });
  } else {
    sendOptions({ hold: false, parameters: S.ruleBeforeHold || "auto" });
  }
});
$("applyClosed").addEventListener("click", () => sendOptions({ closed: [true, $("closedV").checked] }));

$("addPoint").addEventListener("click", () => {
  if (!S.selected) return message("select a point first");
  const r = S.rows[S.selected.row], i = S.selected.index;
  const a = r[i], b = r[i + 1] || r[i - 1] || a.map((x) => x + S.diagonal / 100);
  const p = a.map((x, k) => (r[i + 1] ? (x + b[k]) / 2 : 2 * x - b[k]));
  const sel = { row: S.selected.row, index: i + 1 };
  S.fns.run(api.edit({ op: "insert", row: sel.row, index: sel.index, point: p }), () => { S.selected = sel; });
});
$("delPoint").addEventListener("click", () => {
  if (!S.selected) return message("select a point first");
  const { row, index } = S.selected;
  S.fns.run(api.edit({ op: "delete", row, index }),
    () => { S.selected = { row, index: Math.min(index, S.rows[row].length - 1) }; });
});
$("addRow").addEventListener("click", () => {
  if (!S.selected) return message("select a point of the row first");
  const j = S.selected.row, r = S.rows[j], nx = S.rows[j + 1];
  const pts = nx && nx.length === r.length ? r.map((p, i) => p.map((x, a) => (x + nx[i][a]) / 2))
    : r.map((p) => [p[0], p[1], p[2] + S.diagonal / 50]);
  S.fns.run(api.edit({ op: "insert_row", row: j + 1, points: pts }));
});
$("delRow").addEventListener("click", () => {
  if (!S.selected) return message("select a point of the row first");
  const row = S.selected.row;
  // The selection goes with the row: nothing selected after it (no stale row index).
  S.fns.run(api.edit({ op: "delete_row", row }), () => { S.selected = null; });
});
$("undo").addEventListener("click", () => S.fns.run(api.undo()));
$("redo").addEventListener("click", () => S.fns.run(api.redo()));
window.addEventListener("keydown", (e) => {
  if (e.target instanceof HTMLInputElement && e.target.type !== "checkbox" && e.target.type !== "range") return;
  const k = e.key.toLowerCase();
  if ((e.ctrlKey || e.metaKey) && k === "z") { e.preventDefault(); S.fns.run(e.shiftKey ? api.redo() : api.undo()); }
  else if ((e.ctrlKey || e.metaKey) && k === "y") { e.preventDefault(); S.fns.run(api.redo()); }
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

export { updateMarkers };
