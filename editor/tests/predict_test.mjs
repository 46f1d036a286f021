// The drag's prediction (editor/js/predict.js, docs/editor.md "Latency"), in Debian's Chromium
// (headless, software GL) with real mouse events: where the quick refit is linear (counts held,
// parameters uniform) the page draws S0 + g d at every pointer move itself, and that IS the
// refit: the control points it shows equal the server's quick refit of the same position
// within 1e-9 of their size, mid-drag and for every answer; where the parameters move with the
// point (centripetal) the server says so and the drag waits for its answers as before.
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
const { idle, settled, version, consistent, clickPoint, drag } = pageHelpers(() => ctx);

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

test("centripetal: the refit is not linear, no prediction, the server's answers are drawn", async () => {
  await useOptions({ hold: false });
  const st = await useOptions({ parameters: "centripetal", hold: true });
  assert.equal(st.report.parameters, "centripetal");
  const s = await clickPoint(10, 12);
  const v = await version();
  const k = await influenceOf(10, 12, v);
  assert.equal(k.linear, false);
  // Either reason: the rule's parameters move with the point, or the full fit is the two
  // stages' (their counts searched per row when one misses T).
  assert.match(k.why, /centripetal move with the point|two stages/);
  await page.evaluate(() => { const h = window.sfitEditor; h.latencies = []; h.predictionChecks = []; });
  await drag(s, 20, 25, { steps: 12 });
  await settled(v + 1);
  const lat = await page.evaluate(() => window.sfitEditor.latencies.filter((l) => l.phase === "drag"));
  assert.ok(lat.length >= 1, "the server's answers drawn");
  assert.equal(lat.filter((l) => l.predicted).length, 0, "nothing predicted");
  assert.deepEqual(await page.evaluate(() => window.sfitEditor.predictionChecks), []);
  await consistent("after a drag without prediction");
});
