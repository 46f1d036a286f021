// The editor's JSON API against the real server on 127.0.0.1: the token, the Host header,
// bad requests (400, state unchanged, server alive), edits, undo/redo over 100 steps, the
// drag, save with INPUT.bak, exports, and a clean end on SIGTERM.
import { test, before, after } from "node:test";
import assert from "node:assert/strict";
import { readFileSync, existsSync, statSync } from "node:fs";
import { join } from "node:path";
import { startEditor } from "./browser.mjs";
import { client, request } from "./api.mjs";
import { evaluate } from "../js/bspline.js";
import { unpack } from "../js/pack.js";

const SFIT = process.env.SFIT_CLI;
const EXAMPLES = process.env.SFIT_EXAMPLES;
if (!SFIT || !EXAMPLES) throw new Error("set SFIT_CLI and SFIT_EXAMPLES (CTest does)");
const ROWS = join(EXAMPLES, "ship_px121_stations.rows");

let ed, api, initial;
before(async () => {
  ed = await startEditor(SFIT, ROWS);
  api = client(ed);
  initial = (await api.get("/api/state")).json;
});
after(async () => { if (ed) await ed.stop(); });

// Every point within T per axis on the surface of `st` (evaluated here, independently).
function assertWithinT(st) {
  const t = st.report.tolerance, slack = st.report.roundoff;
  st.rows.forEach((row, j) => row.forEach((p, i) => {
    const s = evaluate(st.surface, st.u[j][i], st.v_points ? st.v_points[j][i] : st.v[j]);
    for (let a = 0; a < 3; a++)
      assert.ok(Math.abs(s[a] - p[a]) <= t[a] * (1 + 1e-9) + slack,
        `row ${j} point ${i} axis ${a}: |S - D| = ${Math.abs(s[a] - p[a])} > T = ${t[a]}`);
  }));
}

async function assertUnchanged(what) {
  const now = (await api.get("/api/state")).json;
  assert.equal(now.version, initial.version, `${what}: version changed`);
  assert.deepEqual(now.surface, initial.surface, `${what}: surface changed`);
  assert.deepEqual(now.rows, initial.rows, `${what}: rows changed`);
}

test("the initial state: rows, surface in the contract, report, final, within T", () => {
  assert.equal(initial.rows.length, 11);
  assert.equal(initial.surface.type, "bspline_surface");
  assert.equal(initial.final, true);
  assert.equal(initial.checked, true);
  assert.equal(initial.report.within_tolerance, true);
  assert.equal(initial.undo, 0);
  assert.equal(initial.redo, 0);
  assertWithinT(initial);
});

test("the token: missing or wrong gets 403, header or ?token= gets in", async () => {
  const none = await request(ed.port, "GET", "/api/state");
  assert.equal(none.status, 403);
  assert.match(none.json.error, /token/);
  const wrong = await request(ed.port, "GET", "/api/state", { token: "0".repeat(32) });
  assert.equal(wrong.status, 403);
  const post = await request(ed.port, "POST", "/api/undo", { body: {} });
  assert.equal(post.status, 403);
  assert.equal((await request(ed.port, "GET", `/api/state?rows=0&token=${ed.token}`)).status, 200);
  assert.equal((await api.get("/api/state?rows=0")).status, 200);
});

test("the Host header: only 127.0.0.1 or localhost with the server's port", async () => {
  for (const host of ["evil.example:" + ed.port, "127.0.0.1:" + (ed.port + 1), "127.0.0.1", "localhost"]) {
    const r = await api.get("/api/state?rows=0", { host });
    assert.equal(r.status, 403, host);
    assert.match(r.json.error, /Host/);
    assert.equal((await request(ed.port, "GET", "/", { host })).status, 403, "the page too: " + host);
  }
  assert.equal((await api.get("/api/state?rows=0", { host: "localhost:" + ed.port })).status, 200);
  assert.equal((await request(ed.port, "GET", "/", { host: "localhost:" + ed.port })).status, 200);
});

test("bad requests get 400 with a JSON error naming the problem; the state stays", async () => {
  const cases = [
    [{ raw: "{not json" }, /JSON/],
    [{ raw: "[1, 2]" }, /object/],
    [{ raw: '{"op": "move", "row": 1, "index": 1, "to": [1, 2, 1e999]}' }, /JSON/],
    [{ body: { op: "teleport" } }, /op.*unknown operation/],
    [{ body: { row: 1 } }, /op: missing/],
    [{ body: { op: "move", row: 99, index: 0, to: [0, 0, 0] } }, /row 99.*no such point/],
    [{ body: { op: "move", row: 1, index: 999, to: [0, 0, 0] } }, /point 999.*no such point/],
    [{ body: { op: "move", row: -1, index: 0, to: [0, 0, 0] } }, /row: must be >= 0/],
    [{ body: { op: "move", row: 1.5, index: 0, to: [0, 0, 0] } }, /row: must be a whole number/],
    [{ body: { op: "move", row: 1, index: 0, to: [0, 0] } }, /to: must be \[x, y, z\]/],
    [{ body: { op: "move", row: 1, index: 0, to: [0, "a", 0] } }, /to: must be a number/],
    [{ body: { op: "move", row: 1, index: 0, to: [0, 0, 0], speed: 3 } }, /speed: unknown field/],
    [{ body: { op: "move", row: 1, index: 0, to: [0, 0, 0], phase: "fly" } }, /phase/],
    [{ body: { op: "delete_row", row: 11 } }, /no such row/],
    [{ body: { op: "insert_row", row: 0, points: [] } }, /at least one point/],
    [{ body: { op: "insert", row: 0, index: 99, point: [0, 0, 0] } }, /no such place/],
    [{ body: { op: "move", row: 1, index: 0, to: [0, 0, 0], seq: -4 } }, /seq/],
  ];
  for (const [o, re] of cases) {
    const r = await request(ed.port, "POST", "/api/edit", { token: ed.token, ...o });
    assert.equal(r.status, 400, JSON.stringify(o));
    assert.equal(typeof r.json.error, "string");
    assert.match(r.json.error, re, JSON.stringify(o));
  }
  for (const [o, re] of [[{ degree: [0, 3] }, /degree/], [{ tolerance: -1 }, /tolerance/],
    [{ tolerance: [1, 2] }, /tolerance/], [{ closed: "u" }, /closed/], [{ parameters: "magic" }, /parameters/],
    [{ search: "slow" }, /search/], [{ knots: 3 }, /knots: must be one of corners, uniform, adaptive/],
    [{ colour: "red" }, /colour: unknown/]]) {
    const r = await api.post("/api/options", o);
    assert.equal(r.status, 400, JSON.stringify(o));
    assert.match(r.json.error, re, JSON.stringify(o));
  }
  for (const [o, re] of [[{}, /format/], [{ format: "docx" }, /cannot export/]]) {
    const r = await api.post("/api/export", o);
    assert.equal(r.status, 400);
    assert.match(r.json.error, re);
  }
  // Oversized: a body over the 64 MiB limit.
  const big = await request(ed.port, "POST", "/api/edit", { token: ed.token, raw: " ".repeat(65 << 20) });
  assert.equal(big.status, 400);
  assert.match(big.json.error, /exceeds/);
  await assertUnchanged("after the bad requests");
});

test("move, insert, delete, row operations refit within T; undo and redo step back and forth", async () => {
  const p = initial.rows[5][3];
  let r = await api.post("/api/edit", { op: "move", row: 5, index: 3, to: [p[0], p[1] + 0.4, p[2] - 0.3] });
  assert.equal(r.status, 200, r.text);
  assert.deepEqual(r.json.rows[5][3], [p[0], p[1] + 0.4, p[2] - 0.3]);
  assert.equal(r.json.final, true);
  assertWithinT(r.json);
  r = await api.post("/api/edit", { op: "insert", row: 2, index: 1, point: initial.rows[2][1].map((x, a) => (x + initial.rows[2][2][a]) / 2) });
  assert.equal(r.json.rows[2].length, initial.rows[2].length + 1);
  assertWithinT(r.json);
  r = await api.post("/api/edit", { op: "delete", row: 4, index: 0 });
  assert.equal(r.json.rows[4].length, initial.rows[4].length - 1);
  r = await api.post("/api/edit", { op: "insert_row", row: 11, points: initial.rows[10].map((q) => [q[0] + 2, q[1], q[2]]) });
  assert.equal(r.json.rows.length, 12);
  assertWithinT(r.json);
  r = await api.post("/api/edit", { op: "replace_row", row: 11, points: initial.rows[10].map((q) => [q[0] + 3, q[1], q[2]]) });
  r = await api.post("/api/edit", { op: "delete_row", row: 11 });
  assert.equal(r.json.rows.length, 11);
  assert.equal(r.json.undo, 6);
  for (let k = 0; k < 6; k++) r = await api.post("/api/undo", {});
  assert.equal(r.json.undo, 0);
  assert.equal(r.json.redo, 6);
  assert.deepEqual(r.json.rows, initial.rows);
  assert.deepEqual(r.json.surface, initial.surface, "undo restores the surface bit for bit");
  assert.equal((await api.post("/api/undo", {})).json.done, false);
  r = await api.post("/api/redo", {});
  assert.deepEqual(r.json.rows[5][3], [p[0], p[1] + 0.4, p[2] - 0.3]);
  r = await api.post("/api/undo", {});
  assert.deepEqual(r.json.surface, initial.surface);
});

test("options: T, degrees, parameters refit; undo restores the old fit", async () => {
  const t = initial.options.tolerance[0];
  let r = await api.post("/api/options", { tolerance: t / 10 });
  assert.equal(r.status, 200, r.text);
  assert.ok(r.json.options.tolerance.every((x) => x === t / 10));
  assert.ok(r.json.report.control_points[0] * r.json.report.control_points[1] >=
            initial.report.control_points[0] * initial.report.control_points[1]);
  assertWithinT(r.json);
  r = await api.post("/api/options", { degree: [2, 2], parameters: "chord" });
  assert.deepEqual(r.json.report.degree, [2, 2]);
  assertWithinT(r.json);
  await api.post("/api/undo", {});
  r = await api.post("/api/undo", {});
  assert.deepEqual(r.json.surface, initial.surface);
  assert.deepEqual(r.json.options, initial.options);
});

test("the option table: the library's, and /api/options checks through it", async () => {
  const r = await api.get("/api/options-table");
  assert.equal(r.status, 200, r.text);
  const spec = (name) => r.json.find((o) => o.name === name);
  assert.deepEqual([spec("degree").min, spec("degree").max, spec("degree").default], [1, 20, 3]);
  assert.deepEqual(spec("parameters").choices,
    ["paper", "uniform", "chord", "centripetal", "geometric", "fewest", "auto"]);
  assert.equal(spec("parameters").default, "auto");
  for (const name of ["method", "norm", "seam", "orient", "rerepresent", "fold_guard", "threads"])
    assert.ok(spec(name), name);
  const bad = await api.post("/api/options", { method: "magic" });
  assert.equal(bad.status, 400);
  assert.match(bad.json.error, /'magic' is not one of surface, sfit01/);
  const ok = await api.post("/api/options", { method: "sfit01" });
  assert.equal(ok.status, 200, ok.text);
  assert.equal(ok.json.options.method, "sfit01");
  assertWithinT(ok.json);
  const back = await api.post("/api/undo", {});
  assert.deepEqual(back.json.options, initial.options);
  // The knot rule too: adaptive knots are asked for and reported, a wrong name is refused.
  assert.deepEqual(spec("knots").choices, ["corners", "uniform", "adaptive"]);
  assert.equal(initial.options.knots, "corners");
  const knots = await api.post("/api/options", { knots: "adaptive" });
  assert.equal(knots.status, 200, knots.text);
  assert.equal(knots.json.options.knots, "adaptive");
  assertWithinT(knots.json);
  const wrong = await api.post("/api/options", { knots: "random" });
  assert.equal(wrong.status, 400);
  assert.match(wrong.json.error, /'random' is not one of corners, uniform, adaptive/);
  await api.post("/api/undo", {});
});

test("a drag is one undo step; its quick refits are not final; stale drag steps are skipped", async () => {
  const p = initial.rows[6][4];
  let r;
  for (let k = 1; k <= 5; k++) {
    r = await api.post("/api/edit", { op: "move", row: 6, index: 4, to: [p[0], p[1], p[2] + 0.1 * k], phase: "drag", seq: 100 + k });
    assert.equal(r.status, 200, r.text);
    assert.equal(r.json.skipped, false);
    assert.equal(r.json.dragging, true);
    assert.equal(r.json.checked, true, "a quick refit checks every point too");
    assert.equal(r.json.rows, undefined, "drag steps omit the rows");
  }
  // ?pack=1: the same surface with its control points packed, exactly (the page's drag steps).
  const packed = await api.post("/api/edit?rows=0&pack=1", { op: "move", row: 6, index: 4, to: [p[0], p[1], p[2] + 0.5], phase: "drag", seq: 110 });
  assert.equal(packed.json.surface.control_points, undefined);
  assert.deepEqual(packed.json.surface.control_points_shape, [packed.json.report.control_points[0], packed.json.report.control_points[1]]);
  const same = (await api.get("/api/state?rows=0")).json;  // the same quick state, unpacked
  assert.equal(same.version, packed.json.version);
  assert.deepEqual(unpack(packed.json.surface), same.surface, "packed control points are exact");
  // ?pack=f32 (the page's drag steps): floats less the middle of the control points' box,
  // within 1e-7 of the box's size of the exact ones; everything else as exact.
  const f32 = await api.post("/api/edit?rows=0&pack=f32", { op: "move", row: 6, index: 4, to: [p[0], p[1], p[2] + 0.5], phase: "drag", seq: 111 });
  assert.equal(f32.json.surface.control_points, undefined);
  assert.equal(f32.json.surface.control_points_f64, undefined);
  assert.equal(typeof f32.json.surface.control_points_f32, "string");
  const exact = (await api.get("/api/state?rows=0")).json;
  assert.equal(exact.version, f32.json.version);
  const near = unpack(f32.json.surface);
  const flat = exact.surface.control_points.flat();
  const lo = [0, 1, 2].map((a) => Math.min(...flat.map((q) => q[a]))), hi = [0, 1, 2].map((a) => Math.max(...flat.map((q) => q[a])));
  const box = Math.max(...[0, 1, 2].map((a) => hi[a] - lo[a]));
  const off = Math.max(...near.control_points.flat().map((q, k) => Math.max(...q.map((x, a) => Math.abs(x - flat[k][a])))));
  assert.ok(off <= 1e-7 * box, `f32 control points off by ${off} (box ${box})`);
  assert.ok(off > 0 || flat.every((q) => q.every((x) => Math.fround(x) === x)), "f32 is not the exact doubles' path");
  assert.deepEqual({ ...near, control_points: null }, { ...exact.surface, control_points: null }, "the rest of the surface as exact");
  r = f32;
  // A step numbered below one already answered (a reloaded page counting from 1 again) is
  // refitted: only a step that a newer one overtook while it waited is skipped
  // (editor_server_test, DragSteps).
  const again = await api.post("/api/edit", { op: "move", row: 6, index: 4, to: [p[0], p[1], p[2] + 0.45], phase: "drag", seq: 101 });
  assert.equal(again.json.skipped, false);
  assert.equal(again.json.version, r.json.version + 1);  // r: the last packed step
  r = await api.post("/api/edit", { op: "move", row: 6, index: 4, to: [p[0], p[1], p[2] + 0.5], phase: "rest", seq: 106 });
  assert.equal(r.json.final, true);
  assert.equal(r.json.dragging, true);
  r = await api.post("/api/edit", { op: "move", row: 6, index: 4, to: [p[0], p[1], p[2] + 0.6], phase: "end", seq: 107 });
  assert.equal(r.json.final, true);
  assert.equal(r.json.dragging, false);
  assert.equal(r.json.undo, 1, "the whole drag is one step");
  assert.deepEqual(r.json.rows[6][4], [p[0], p[1], p[2] + 0.6]);
  assertWithinT(r.json);
  r = await api.post("/api/undo", {});
  assert.deepEqual(r.json.surface, initial.surface);
});

test("undo and redo over more than 100 steps", async () => {
  const p = initial.rows[3][2];
  const n = 105;
  let r;
  for (let k = 1; k <= n; k++)
    r = await api.post("/api/edit?rows=0", { op: "move", row: 3, index: 2, to: [p[0], p[1] + 0.001 * k, p[2]] });
  assert.equal(r.json.undo, n);
  for (let k = 0; k < n; k++) r = await api.post("/api/undo", {});
  assert.equal(r.json.undo, 0);
  assert.deepEqual(r.json.rows, initial.rows);
  assert.deepEqual(r.json.surface, initial.surface);
  for (let k = 0; k < n; k++) r = await api.post("/api/redo", {});
  assert.deepEqual(r.json.rows[3][2], [p[0], p[1] + 0.001 * n, p[2]]);
  for (let k = 0; k < n; k++) r = await api.post("/api/undo", {});
  assert.deepEqual(r.json.surface, initial.surface);
});

test("save writes the rows back to INPUT atomically and keeps INPUT.bak", async () => {
  const original = readFileSync(ed.input, "utf8");
  const p = initial.rows[1][1];
  await api.post("/api/edit", { op: "move", row: 1, index: 1, to: [p[0], p[1] + 0.25, p[2]] });
  let r = await api.post("/api/save", {});
  assert.equal(r.status, 200, r.text);
  assert.equal(readFileSync(ed.input + ".bak", "utf8"), original);
  const saved = readFileSync(ed.input, "utf8");
  assert.ok(saved.startsWith("# name: ship_px121_stations"), "the header comments stay");
  const rows = saved.split(/\n\s*\n/).map((b) => b.split("\n").filter((l) => l && !l.startsWith("#"))
    .map((l) => l.trim().split(/\s+/).map(Number))).filter((b) => b.length);
  const st = (await api.get("/api/state")).json;
  assert.deepEqual(rows, st.rows, "the saved file holds exactly the edited rows");
  // A second save keeps the first backup (the original).
  await api.post("/api/undo", {});
  r = await api.post("/api/save", {});
  assert.equal(readFileSync(ed.input + ".bak", "utf8"), original);
});

test("exports beside INPUT through the writers", async () => {
  const st = (await api.get("/api/state")).json;
  for (const f of st.exports.filter((x) => ["json", "step", "iges", "obj", "stl"].includes(x))) {
    const r = await api.post("/api/export", { format: f });
    assert.equal(r.status, 200, r.text);
    assert.ok(existsSync(r.json.path) && statSync(r.json.path).size > 100, f);
    assert.notEqual(r.json.path, ed.input);
    if (f === "json") {
      const j = JSON.parse(readFileSync(r.json.path, "utf8"));
      const { report, ...surface } = j;
      assert.deepEqual(surface, st.surface);
      assert.equal(report.within_tolerance, true);
    }
  }
  const d = await api.get("/api/export?format=json");
  assert.equal(d.status, 200);
  assert.match(d.headers["content-disposition"], /attachment; filename="ship_px121_stations-edited.json"/);
});

test("the page and three.js are served by the binary itself", async () => {
  const page = await request(ed.port, "GET", "/");
  assert.equal(page.status, 200);
  assert.match(page.text, /importmap/);
  const st = (await api.get("/api/state?rows=0")).json;
  const three = await request(ed.port, "GET", "/vendor/three.module.min.js");
  assert.equal(three.status, st.three ? 200 : 404);
  if (st.three) assert.match(three.text, /REVISION/);
  assert.equal((await request(ed.port, "GET", "/js/app.js")).status, 200);
  assert.equal((await request(ed.port, "GET", "/etc/passwd")).status, 404);
});

test("a second editor on a port in use refuses to start (exit 2)", async () => {
  await assert.rejects(startEditor(SFIT, ROWS, ["--port", String(ed.port)]),
    /exited 2: .*cannot listen on 127\.0\.0\.1:\d+/s);
});

test("SIGTERM ends the server cleanly", async () => {
  const r = await ed.stop();
  ed = null;
  assert.equal(r.code, 0, "exit code");
});
