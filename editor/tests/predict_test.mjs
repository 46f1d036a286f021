// The drag's prediction (editor/js/predict.js, docs/editor-latency.md), in Debian's Chromium
// (headless, software GL) with real mouse events: where the quick refit is linear (counts held,
// parameters uniform) the page draws S0 + g d at every pointer move itself, and that IS the
// refit: the control points it shows equal the server's quick refit of the same position
// within 1e-9 of their size, mid-drag and for every answer. Without the hold too, on the two
// stages' surface and at parameters that move with the points (centripetal): the
// drag's refit is frozen at the drag's start (include/sfit/frozen_refit.h); the influence is asked
// for when the point is selected, not at the press (the request log).
import { test, before, after } from "node:test";
import assert from "node:assert/strict";
import { writeFileSync, mkdtempSync, rmSync } from "node:fs";
import { tmpdir } from "node:os";
import { join } from "node:path";
import { openEditor, pageHelpers } from "./page_helpers.mjs";

const SFIT = process.env.SFIT_CLI;
if (!SFIT) throw new Error("set SFIT_CLI (CTest does)");

// A 30 x 40 terrain (bench/editor_latency.mjs's, smaller).
const dir = mkdtempSync(join(tmpdir(), "sfit-predict-"));
const file = join(dir, "terrain.rows");
let text = "";
for (let j = 0; j < 30; j++) {
  for (let k = 0; k < 40; k++) {
    const s = k / 39, t = j / 29;
    text += `${100 * s} ${100 * t} ${10 * Math.sin(3 * s) * Math.cos(2 * t) + 5 * s * t * t + 0.5 * Math.sin(17 * s + 11 * t)}\n`;
  }
  text += "\n";
}
writeFileSync(file, text);

let ctx, api, page;
before(async () => {
  ctx = await openEditor(SFIT, file);
  ({ api, page } = ctx);
  await page.evaluate(() => { window.sfitEditor.restMs = 1e9; });  // no full fit while the hand rests
});
after(async () => {
  if (ctx) await ctx.close();
  rmSync(dir, { recursive: true, force: true });
});
const { idle, settled, version, consistent, clickPoint, drag, deselect } = pageHelpers(() => ctx);

// The session's options set through the API, then shown by the page.
async function useOptions(o) {
  const r = await api.post("/api/options", o);
  assert.equal(r.status, 200, JSON.stringify(r.json));
  await page.evaluate(() => window.sfitEditor.refresh());
  await idle();
  return r.json;
}
// The largest difference of two nets of control points over the larger's largest coordinate.
function offOf(a, b) {
  assert.equal(a.length, b.length, "rows of control points");
  let big = 0, off = 0;
  a.forEach((r, i) => {
    assert.equal(r.length, b[i].length, "control points per row");
    r.forEach((p, j) => p.forEach((x, c) => {
      big = Math.max(big, Math.abs(b[i][j][c]));
      off = Math.max(off, Math.abs(x - b[i][j][c]));
    }));
  });
  return off / big;
}
const influenceOf = (row, index, v) => page.waitForFunction((r, i, v) => {
  const k = window.sfitEditor.influence;
  return k && k.row === r && k.index === i && k.version === v && k;
}, { timeout: 30000 }, row, index, v).then((h) => h.jsonValue());

test("held, uniform parameters: the page draws the refit itself, and it is the server's refit", async () => {
  const st = await useOptions({ parameters: "uniform", hold: true });
  assert.equal(st.report.parameters, "uniform");
  const s = await clickPoint(15, 20);
  const v = await version();
  const k = await influenceOf(15, 20, v);
  assert.equal(k.linear, true, `linear: ${k.why}`);
  await page.evaluate(() => { const h = window.sfitEditor; h.latencies = []; h.predictionChecks = []; });
  // Mid-drag: the hand stops, every move answered; what the page shows against the server.
  await drag(s, 25, -30, { steps: 20, up: false });
  await page.waitForFunction(() => window.sfitEditor.movesSettled(), { timeout: 30000 });
  const shown = await page.evaluate(() => ({ cp: window.sfitEditor.surfaceShown(), p: window.sfitEditor.rows()[15][20] }));
  const server = (await api.get("/api/state")).json;
  assert.equal(server.dragging, true, "the drag goes on");
  assert.equal(server.final, false, "the server shows its quick refit");
  assert.deepEqual(server.rows[15][20], shown.p, "the server has the page's position");
  assert.ok(offOf(shown.cp, server.surface.control_points) <= 1e-9,
    `the page's control points are the server's quick refit: ${offOf(shown.cp, server.surface.control_points)}`);
  await page.mouse.up();
  await settled(v + 1);
  const lat = await page.evaluate(() => window.sfitEditor.latencies.filter((l) => l.phase === "drag"));
  // Every move drawn was drawn from the prediction (none waited for the server), however many
  // a newer one overtook on a loaded machine.
  const predicted = lat.filter((l) => l.predicted).length;
  assert.ok(predicted >= 5 && predicted === lat.length, `moves drawn from the prediction: ${predicted} of ${lat.length} drawn (20 moves)`);
  const checks = await page.evaluate(() => window.sfitEditor.predictionChecks);
  assert.ok(checks.length >= 1, "the server's answers were compared with their predictions");
  for (const c of checks) assert.ok(c.off <= 1e-9, `answer ${c.seq}: off by ${c.off} of the control points' size`);
  await consistent("after a predicted drag");
});

// The influence requests the page made (puppeteer's request log), each with its (row, index)
// and the time it went out (Node's clock, as the mouse events below).
const influenceLog = [];
function logInfluence(req) {
  if (req.url().includes("/api/influence")) influenceLog.push({ t: performance.now(), ...JSON.parse(req.postData() || "{}") });
}

// Without the hold, whatever made the full fit: the drag's refit is least squares at the fit's
// counts, knots and parameters frozen at the drag's start, so the page predicts every move;
// the influence is asked for when the point is selected, never at the press.
async function unheldDrag(options, method, rule, row, index) {
  await deselect();  // the point is selected below: its influence is asked for then
  page.on("request", logInfluence);
  try {
    influenceLog.length = 0;
    await useOptions({ hold: false });
    const st = await useOptions({ ...options, hold: false });
    assert.equal(st.options.hold, false);
    if (method) assert.equal(st.report.method, method, JSON.stringify(st.report));
    if (rule) assert.equal(st.report.parameters, rule, JSON.stringify([st.options, st.report.method, st.report.stop_reason, st.best_effort]));
    const clicked = performance.now();
    const s = await clickPoint(row, index);
    const v = await version();
    const k = await influenceOf(row, index, v);
    assert.equal(k.linear, true, `linear: ${k.why}`);
    await page.evaluate(() => { const h = window.sfitEditor; h.latencies = []; h.predictionChecks = []; });
    const pressed = performance.now();
    await drag(s, -20, 25, { steps: 16, up: false });
    await page.waitForFunction(() => window.sfitEditor.movesSettled(), { timeout: 30000 });
    const shown = await page.evaluate((r, i) => ({ cp: window.sfitEditor.surfaceShown(), p: window.sfitEditor.rows()[r][i] }), row, index);
    const server = (await api.get("/api/state")).json;
    assert.equal(server.dragging, true, "the drag goes on");
    assert.equal(server.final, false, "the server shows its quick refit");
    assert.match(server.report.stop_reason, /frozen/, "the quick refit, frozen for the drag");
    assert.deepEqual(server.report.control_points, st.report.control_points, "the counts of the drag's start");
    assert.deepEqual(server.rows[row][index], shown.p, "the server has the page's position");
    const off = offOf(shown.cp, server.surface.control_points);
    assert.ok(off <= 1e-9, `the page's control points are the server's quick refit: ${off}`);
    const released = performance.now();
    await page.mouse.up();
    await settled(v + 1);
    // The request log: the influence of the point went out when it was selected (before the
    // press), and none went out between the press and the release.
    const asked = influenceLog.filter((r) => r.row === row && r.index === index && r.t >= clicked && r.t < pressed);
    assert.ok(asked.length >= 1, `influence asked on select: ${JSON.stringify(influenceLog)} (click ${clicked}, press ${pressed})`);
    const during = influenceLog.filter((r) => r.t >= pressed && r.t <= released);
    assert.deepEqual(during, [], "no influence asked for between the press and the release");
    const lat = await page.evaluate(() => window.sfitEditor.latencies.filter((l) => l.phase === "drag"));
    const predicted = lat.filter((l) => l.predicted).length;
    assert.ok(predicted >= 5 && predicted === lat.length, `moves drawn from the prediction: ${predicted} of ${lat.length} drawn (16 moves)`);
    const checks = await page.evaluate(() => window.sfitEditor.predictionChecks);
    assert.ok(checks.length >= 1, "the server's answers were compared with their predictions");
    for (const c of checks) assert.ok(c.off <= 1e-9, `answer ${c.seq}: off by ${c.off} of the control points' size`);
    return { pressed };
  } finally {
    page.off("request", logInfluence);
  }
}

test("not held, the two stages' surface: predicted, the page's control points are the server's", async () => {
  await unheldDrag({ method: "sfit01", parameters: "paper" }, "sfit01", "paper", 15, 20);
  await consistent("after a predicted drag on the two stages' surface");
});

test("not held, centripetal parameters: predicted (frozen for the drag)", async () => {
  // The surface search's or the two stages' surface, whichever the search kept (here the two
  // stages' at centripetal parameters). Chord parameters: tests/editor/influence_test.cpp.
  await unheldDrag({ method: "surface", parameters: "centripetal" }, null, "centripetal", 10, 12);
  await consistent("after a predicted drag, parameters centripetal");
});
