// `sfit edit` and the files it saves, against the real server: weighted rows keep their weight
// column, a byte-order mark and the header comments stay, INPUT.bak is written once and never
// replaced in a later session, a symbolic link is saved through (its target written, the link
// and the mode kept), read-only inputs and inputs with other hard links are refused with
// nothing written; drag steps after a reload, in a second tab or after a huge seq are refitted;
// start-up errors name the file; SIGTERM ends the server promptly, even during a refit.
import { test } from "node:test";
import assert from "node:assert/strict";
import { spawn } from "node:child_process";
import { readFileSync, writeFileSync, mkdtempSync, rmSync, symlinkSync, chmodSync, statSync,
  existsSync, linkSync, lstatSync, realpathSync, readdirSync } from "node:fs";
import { tmpdir } from "node:os";
import { join } from "node:path";
import { client } from "./api.mjs";

const SFIT = process.env.SFIT_CLI;
const EXAMPLES = process.env.SFIT_EXAMPLES;
if (!SFIT || !EXAMPLES) throw new Error("set SFIT_CLI and SFIT_EXAMPLES (CTest does)");
const SHIP = readFileSync(join(EXAMPLES, "ship_px121_stations.rows"), "utf8");

// `sfit edit INPUT` on the path as given (no copy); resolves once it listens.
function start(input, extra = []) {
  const proc = spawn(SFIT, ["edit", input, "--no-browser", ...extra], { stdio: ["ignore", "ignore", "pipe"] });
  let err = "";
  const exited = new Promise((res) => proc.on("exit", (code, signal) => res({ code, signal, err })));
  return new Promise((resolve, reject) => {
    exited.then((r) => reject(Object.assign(new Error(`sfit edit exited ${r.code}: ${err}`), r)));
    proc.stderr.on("data", (d) => {
      err += d;
      const m = err.match(/at http:\/\/127\.0\.0\.1:(\d+)\/\?token=([0-9a-f]+)/);
      if (m) resolve({ port: Number(m[1]), token: m[2], proc, exited, stderr: () => err,
        async stop() { proc.kill("SIGTERM"); return exited; } });
    });
  });
}

function folder() { return mkdtempSync(join(tmpdir(), "sfit-edit-files-")); }

// The ship's rows with a 4th number on every data line: weights 0.5, 1, 1.5, 2, 0.5, ...
function weighted() {
  let k = 0;
  return SHIP.split("\n").map((l) => (l.trim() && !l.trim().startsWith("#") ? `${l.trim()} ${0.5 * (1 + (k++ % 4))}` : l)).join("\n");
}
function dataLines(text) { return text.split(/\r?\n/).filter((l) => l.trim() && !l.trim().startsWith("#")); }
function weightsOf(text) { return dataLines(text).map((l) => Number(l.trim().split(/\s+/)[3])); }

test("weighted rows: edits refused with a reason, save keeps the weight column, INPUT.bak once over two sessions", async () => {
  const dir = folder(), input = join(dir, "w.rows"), original = weighted();
  writeFileSync(input, original);
  try {
    for (let session = 0; session < 2; session++) {
      const ed = await start(input);
      const api = client(ed);
      const st = (await api.get("/api/state")).json;
      const p = st.rows[2][2];
      for (const body of [{ op: "move", row: 2, index: 2, to: [p[0], p[1] + 0.1, p[2]] },
        { op: "insert_row", row: 1, points: st.rows[1] }, { op: "delete_row", row: 1 }]) {
        const r = await api.post("/api/edit", body);
        assert.equal(r.status, 400, JSON.stringify(body));
        assert.equal(r.json.error, "weights: edits of weighted rows are not supported yet");
      }
      const t = (await api.post("/api/options", { tolerance: st.options.tolerance[0] * 2 })).json;
      assert.equal(t.options.tolerance[0], st.options.tolerance[0] * 2, "options still refit");
      const r = await api.post("/api/save", {});
      assert.equal(r.status, 200, r.text);
      assert.equal(r.json.weights, true);
      assert.equal(r.json.backup, input + ".bak");
      assert.equal(r.json.backup_written, session === 0, "the backup is written once");
      const saved = readFileSync(input, "utf8");
      assert.deepEqual(weightsOf(saved), weightsOf(original), "every weight saved");
      assert.deepEqual(dataLines(saved).map((l) => l.split(/\s+/).slice(0, 3).map(Number)),
        st.rows.flat(), "the points saved");
      assert.ok(saved.startsWith("# name: ship_px121_stations"), "the header comments stay");
      assert.equal(readFileSync(input + ".bak", "utf8"), original, "the original survives");
      assert.equal((await ed.stop()).code, 0);
    }
  } finally { rmSync(dir, { recursive: true, force: true }); }
});

test("a UTF-8 byte-order mark and the header comments stay on save", async () => {
  const dir = folder(), input = join(dir, "bom.rows");
  writeFileSync(input, "\uFEFF" + SHIP);
  try {
    const ed = await start(input);
    const api = client(ed);
    const p = (await api.get("/api/state")).json.rows[3][1];
    assert.equal((await api.post("/api/edit", { op: "move", row: 3, index: 1, to: [p[0], p[1] + 0.2, p[2]] })).status, 200);
    assert.equal((await api.post("/api/save", {})).status, 200);
    const saved = readFileSync(input, "utf8");
    const head = SHIP.split("\n").filter((l, i, a) => a.slice(0, i + 1).every((x) => !x.trim() || x.startsWith("#")));
    assert.ok(saved.startsWith("\uFEFF" + head.join("\n") + "\n"), saved.slice(0, 300));
    const st = (await api.get("/api/state")).json;
    assert.equal(st.rows[3][1][1], p[1] + 0.2);
    assert.deepEqual(dataLines(saved).map((l) => l.split(" ").map(Number)), st.rows.flat(), "the edited rows saved");
    await ed.stop();
  } finally { rmSync(dir, { recursive: true, force: true }); }
});

test("save through a symbolic link writes its target, keeps the link and the mode", async () => {
  const dir = folder(), target = join(dir, "real.rows"), link = join(dir, "link.rows");
  writeFileSync(target, SHIP);
  chmodSync(target, 0o604);
  symlinkSync("real.rows", link);
  try {
    const ed = await start(link);
    const api = client(ed);
    const p = (await api.get("/api/state")).json.rows[0][0];
    await api.post("/api/edit", { op: "move", row: 0, index: 0, to: [p[0], p[1] + 0.3, p[2]] });
    const r = await api.post("/api/save", {});
    assert.equal(r.status, 200, r.text);
    assert.equal(r.json.saved, link);
    assert.equal(r.json.written, realpathSync(target));
    assert.ok(lstatSync(link).isSymbolicLink(), "the link stays a link");
    assert.equal(dataLines(readFileSync(target, "utf8"))[0].split(" ")[1], String(p[1] + 0.3));
    assert.equal(statSync(target).mode & 0o7777, 0o604, "the mode stays");
    assert.equal(readFileSync(link + ".bak", "utf8"), SHIP);
    await ed.stop();
  } finally { rmSync(dir, { recursive: true, force: true }); }
});

test("a read-only input or one with other hard links: save refused, nothing written", async () => {
  const dir = folder(), ro = join(dir, "ro.rows"), hard = join(dir, "hard.rows");
  writeFileSync(ro, SHIP);
  writeFileSync(hard, SHIP);
  linkSync(hard, join(dir, "other.rows"));
  try {
    const ed = await start(ro);
    chmodSync(ro, 0o444);
    let r = await client(ed).post("/api/save", {});
    assert.equal(r.status, 500);
    assert.equal(r.json.code, "output-write");
    assert.equal(r.json.error, `${ro}: cannot save: '${ro}' is read-only (mode 0444); nothing written`);
    await ed.stop();
    const ed2 = await start(hard);
    r = await client(ed2).post("/api/save", {});
    assert.equal(r.status, 500);
    assert.equal(r.json.error, `${hard}: cannot save: '${hard}' has 2 hard links and saving (a new file ` +
      "renamed over it) would break them; copy it to a file of its own to edit it; nothing written");
    await ed2.stop();
    assert.equal(readFileSync(ro, "utf8"), SHIP);
    assert.equal(readFileSync(hard, "utf8"), SHIP);
    assert.deepEqual(readdirSync(dir).sort(), ["hard.rows", "other.rows", "ro.rows"], "no backup, no temporary file");
  } finally { rmSync(dir, { recursive: true, force: true }); }
});

test("drag steps after a reload, in a second tab or after a huge seq are refitted; seq is bounded", async () => {
  const dir = folder(), input = join(dir, "ship.rows");
  writeFileSync(input, SHIP);
  try {
    const ed = await start(input);
    const api = client(ed);
    const p = (await api.get("/api/state")).json.rows[6][4];
    const step = (dz, seq, phase = "drag", extra = {}) =>
      api.post("/api/edit", { op: "move", row: 6, index: 4, to: [p[0], p[1], p[2] + dz], phase, seq, ...extra });
    // The first page drags far into its numbering, then is reloaded mid-drag (no "end").
    for (let k = 0; k < 3; k++) assert.equal((await step(0.01 * k, 5000 + k)).json.skipped, false);
    // The reloaded page counts from 1 again; a second tab (its own client id) too.
    for (const [seq, extra] of [[1, {}], [2, {}], [1, { client: "tab-2" }], [2, { client: "tab-2" }]]) {
      const r = await step(0.02 * seq, seq, "drag", extra);
      assert.equal(r.status, 200, r.text);
      assert.equal(r.json.skipped, false, `seq ${seq} ${JSON.stringify(extra)}`);
      assert.equal(r.json.dragging, true);
    }
    // The largest seq taken, then small ones: not frozen.
    assert.equal((await step(0.05, 9007199254740991)).json.skipped, false);
    const after = await step(0.06, 3);
    assert.equal(after.json.skipped, false, "a huge seq does not freeze the drags after it");
    const end = await step(0.07, 4, "end");
    assert.equal(end.json.dragging, false);
    assert.deepEqual((await api.get("/api/state")).json.rows[6][4], [p[0], p[1], p[2] + 0.07]);
    for (const [seq, msg] of [[9007199254740992, "seq: must be at most 9007199254740991, got 9007199254740992"],
      [-1, "seq: must be a whole number >= 0, got -1"]]) {
      const r = await step(0.1, seq);
      assert.equal(r.status, 400);
      assert.equal(r.json.error, msg);
    }
    const c = await step(0.1, 1, "drag", { client: 7 });
    assert.equal(c.json.error, "client: must be a string of at most 64 characters");
    await ed.stop();
  } finally { rmSync(dir, { recursive: true, force: true }); }
});

test("start-up errors name the file", async () => {
  const dir = folder();
  try {
    const cases = [
      ["bad.rows", "0 0 0\n1 0 x\n", 4, /^sfit: error: .*bad\.rows:2:5: row 0, point 1: /m],
      ["one.rows", "0 0 0\n1 0 0\n2 0 1\n", 5, /^sfit: error: .*one\.rows:1: row 0: one row makes a curve, not a surface/m],
    ];
    for (const [name, text, code, re] of cases) {
      writeFileSync(join(dir, name), text);
      const r = await start(join(dir, name)).then(() => assert.fail("started"), (e) => e);
      if (code !== null) assert.equal(r.code, code, r.err);
      assert.notEqual(r.code, 0);
      assert.notEqual(r.code, 8);
      assert.match(r.err, re);
    }
  } finally { rmSync(dir, { recursive: true, force: true }); }
});

test("SIGTERM during a long refit: the server ends promptly, the refit abandoned", async () => {
  // Two long smooth rows start quickly; one typed move making an outlier sends the full refit
  // into a long search (minutes before the count search was bounded).
  const dir = folder(), input = join(dir, "long.rows"), n = 30000;
  const row = (y) => Array.from({ length: n }, (_, i) => `${i / n} ${y} ${Math.sin(6 * i / n) * (1 + y)}`).join("\n");
  writeFileSync(input, row(0) + "\n\n" + row(1) + "\n");
  try {
    const ed = await start(input, ["--tol", "0.01"]);  // some 4 s; the move: over 40 s
    const api = client(ed);
    let answered = false;
    const move = api.post("/api/edit?rows=0", { op: "move", row: 1, index: n / 2, to: [0.5, 1, 3] })
      .then(() => { answered = true; }, () => {});
    await new Promise((r) => setTimeout(r, 500));
    const sent = Date.now();
    const r = await ed.stop();
    const took = Date.now() - sent;
    await move;
    assert.equal(r.code, 0, r.err);
    // Not a timing assertion: a bound ten times the grace, against the minutes of the refit.
    assert.ok(took < 15000, `exit ${took} ms after SIGTERM`);
    // The refit may end just before the stop (the count search is bounded now), its answer
    // lost with the connection: then the server says plainly that it stopped.
    assert.match(r.err, answered ? /sfit: stopped/ : /sfit: stopped( \(the refit under way was abandoned\))?\n/);
    console.log(`# SIGTERM to exit: ${took} ms; the move ${answered ? "had answered" : "was abandoned"}`);
  } finally { rmSync(dir, { recursive: true, force: true }); }
});
