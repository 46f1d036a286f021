// The editor's JSON API (docs/editor-api.md), with the token from the page's address.
import { unpack } from "./pack.js";
const token = new URLSearchParams(location.search).get("token") || "";

export class ApiError extends Error {}

// Requests that may run a full search (all but drag steps and the light calls): while one is
// out, the page shows the search's progress (GET /api/progress).
let full = 0;
export const fullInFlight = () => full;
const light = (path, body) => path.startsWith("/api/progress") || path === "/api/cancel" ||
  (path.startsWith("/api/state") || path === "/api/options-table" || path === "/api/influence") || (body && body.phase === "drag");

export async function call(method, path, body) {
  const counted = !light(path, body);
  if (counted) full++;
  try { return await send(method, path, body); } finally { if (counted) full--; }
}

async function send(method, path, body) {
  const res = await fetch(path, {
    method,
    headers: { "X-Sfit-Token": token, "Content-Type": "application/json" },
    body: body === undefined ? undefined : JSON.stringify(body),
  });
  const j = await res.json();
  if (!res.ok) throw new ApiError(j.error || `HTTP ${res.status}`);
  return j;
}

export const getState = (rows = true) => call("GET", `/api/state${rows ? "" : "?rows=0"}`);
// A drag step's answer comes with its control points packed as floats for drawing (base64,
// far cheaper than JSON numbers for thousands of them, half the bytes of exact doubles; the
// final surface at rest comes exact); unpacked here into the surface contract.
// `exact`: a drag step's control points packed exactly (doubles), to compare with the page's
// own prediction of the step (predict.js).
export const edit = async (op, rows = true, exact = false) => {
  const drag = op.phase === "drag";
  const pack = drag ? (rows ? "?" : "&") + (exact ? "pack=1" : "pack=f32") : "";
  const st = await call("POST", `/api/edit${rows ? "" : "?rows=0"}${pack}`, op);
  if (st.surface && st.surface.control_points_shape) unpack(st.surface);
  return st;
};

// The moved point's influence on the quick refit (docs/editor-latency.md; predict.js).
export const influence = (row, index) => call("POST", "/api/influence", { row, index });
export const undo = () => call("POST", "/api/undo", {});
export const redo = () => call("POST", "/api/redo", {});
export const setOptions = (o) => call("POST", "/api/options", o);
export const getOptionsTable = () => call("GET", "/api/options-table");
export const save = () => call("POST", "/api/save", {});
export const exportBeside = (format) => call("POST", "/api/export", { format });
export const downloadUrl = (format) =>
  `/api/export?format=${encodeURIComponent(format)}&token=${encodeURIComponent(token)}`;
export const search = (o) => call("POST", "/api/search", o || {});
export const progress = () => call("GET", "/api/progress");
export const cancel = () => call("POST", "/api/cancel", {});
