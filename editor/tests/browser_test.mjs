// The editor in a real browser: Debian's Chromium, headless with software GL, driven by
// puppeteer-core. Loads the page on a bundled data set, checks the surface is drawn, drags a
// point with real mouse events, waits for the final refit, checks the state (the point moved,
// every point within T), undoes with Ctrl-Z (the surface back bit for bit), exports STEP and
// reads it back with OpenCASCADE, and takes the screenshot of docs/editor.md.
import { test, before, after } from "node:test";
import assert from "node:assert/strict";
import { execFileSync } from "node:child_process";
import { join } from "node:path";
import { skipUnlessChromium, loadPuppeteer, startEditor, launch, openPage } from "./browser.mjs";
import { client } from "./api.mjs";
import { evaluate } from "../js/bspline.js";
import { settledAt } from "./page_helpers.mjs";

skipUnlessChromium();
const SFIT = process.env.SFIT_CLI;
const EXAMPLES = process.env.SFIT_EXAMPLES;
const OUT = process.env.SFIT_OUT || ".";
if (!SFIT || !EXAMPLES) throw new Error("set SFIT_CLI and SFIT_EXAMPLES (CTest does)");
const puppeteer = await loadPuppeteer();

let ed, api, browser, page, initial;
const errors = [];
before(async () => {
  ed = await startEditor(SFIT, join(EXAMPLES, "ship_px121_stations.rows"));
  api = client(ed);
  initial = (await api.get("/api/state")).json;
  browser = await launch(puppeteer);
  page = await openPage(browser, ed.url, errors);
});
after(async () => {
  if (browser) await browser.close();
  if (ed) await ed.stop();
});

const settled = (minVersion) => settledAt(page, minVersion);

function assertWithinT(st) {
  const t = st.report.tolerance, slack = st.report.roundoff;
  st.rows.forEach((row, j) => row.forEach((p, i) => {
    const s = evaluate(st.surface, st.u[j][i], st.v_points ? st.v_points[j][i] : st.v[j]);
    for (let a = 0; a < 3; a++)
      assert.ok(Math.abs(s[a] - p[a]) <= t[a] * (1 + 1e-9) + slack, `row ${j} point ${i} axis ${a}`);
  }));
}

test("the page draws the surface (the canvas is not blank)", async () => {
  await page.evaluate(() => window.sfitEditor.nextFrame());
  const pixels = await page.evaluate(() => {
    const c = document.querySelector("#view canvas");
    const t = document.createElement("canvas");
    t.width = c.width; t.height = c.height;
    const g = t.getContext("2d");
    g.drawImage(c, 0, 0);
    const d = g.getImageData(0, 0, t.width, t.height).data;
    const bg = [0x1d, 0x20, 0x24];
    let drawn = 0;
    const colours = new Set();
    for (let i = 0; i < d.length; i += 4) {
      if (Math.abs(d[i] - bg[0]) + Math.abs(d[i + 1] - bg[1]) + Math.abs(d[i + 2] - bg[2]) > 24) drawn++;
      colours.add((d[i] >> 3) * 1024 + (d[i + 1] >> 3) * 32 + (d[i + 2] >> 3));
    }
    return { drawn, total: d.length / 4, colours: colours.size };
  });
  assert.ok(pixels.drawn > 0.05 * pixels.total, `only ${pixels.drawn} of ${pixels.total} pixels drawn`);
  assert.ok(pixels.colours > 20, `only ${pixels.colours} colours: not shaded`);
  const status = await page.$eval("#status", (e) => e.textContent);
  assert.match(status, /final surface/);
  const report = await page.$eval("#report", (e) => e.textContent);
  assert.match(report, new RegExp(`${initial.report.control_points[0]} × ${initial.report.control_points[1]}`));
  assert.match(report, /within T/);
});

test("dragging a point with the mouse refits: the point moved, every point within T, one undo step", async () => {
  const row = 5, index = 4;
  const before = initial.rows[row][index];
  const v0 = await page.evaluate(() => window.sfitEditor.state.version);
  const s = await page.evaluate((r, i) => window.sfitEditor.screenOf(r, i), row, index);
  await page.mouse.click(s.x, s.y);  // select, then drag
  await page.mouse.move(s.x, s.y);
  await page.mouse.down();
  for (let k = 1; k <= 12; k++) {
    await page.mouse.move(s.x + 3 * k, s.y - 4 * k);
    await new Promise((r) => setTimeout(r, 15));
  }
  await new Promise((r) => setTimeout(r, 400));  // the hand rests: the final refit
  await page.mouse.up();
  await settled(v0 + 1);
  const st = (await api.get("/api/state")).json;
  const after = st.rows[row][index];
  const moved = Math.hypot(after[0] - before[0], after[1] - before[1], after[2] - before[2]);
  assert.ok(moved > 1e-3 * initial.report.tolerance[0], `the point moved by ${moved}`);
  st.rows.forEach((r, j) => r.forEach((p, i) => {
    if (j !== row || i !== index) assert.deepEqual(p, initial.rows[j][i], "only the dragged point moved");
  }));
  assert.equal(st.final, true);
  assert.equal(st.undo, 1, "the whole drag is one undo step");
  assert.equal(st.report.within_tolerance, true);
  assertWithinT(st);
  assert.notDeepEqual(st.surface, initial.surface);
  const shown = await page.evaluate(() => window.sfitEditor.state.version);
  assert.equal(shown, st.version, "the page shows the newest state");
  const lat = await page.evaluate(() => window.sfitEditor.latencies);
  assert.ok(lat.some((l) => l.phase === "drag" && !l.final), "quick refits were shown while dragging");
  assert.ok(lat.some((l) => l.final), "the final refit was shown");
});

test("Ctrl-Z restores the previous surface bit for bit; Ctrl-Y redoes", async () => {
  const v = await page.evaluate(() => window.sfitEditor.state.version);
  await page.click("#mode");  // focus away from the canvas; keys go to the window
  await page.keyboard.press("Escape");
  await page.keyboard.down("Control");
  await page.keyboard.press("z");
  await page.keyboard.up("Control");
  await settled(v + 1);
  let st = (await api.get("/api/state")).json;
  assert.equal(st.undo, 0);
  assert.deepEqual(st.rows, initial.rows);
  assert.deepEqual(st.surface, initial.surface, "the surface is the one before the drag, bit for bit");
  const shownSurface = await page.evaluate(() => window.sfitEditor.state.surface);
  assert.deepEqual(shownSurface, initial.surface);
  await page.keyboard.down("Control");
  await page.keyboard.press("y");
  await page.keyboard.up("Control");
  await settled(v + 2);
  st = (await api.get("/api/state")).json;
  assert.equal(st.undo, 1);
});

test("the modes draw: deviation, zebra, curvature, control net", async () => {
  for (const mode of ["deviation", "zebra", "curvature", "shaded"]) {
    await page.select("#mode", mode);
    await page.evaluate(() => window.sfitEditor.nextFrame());
  }
  await page.click("#net");
  await page.evaluate(() => window.sfitEditor.nextFrame());
  assert.deepEqual(errors, []);
});

test("export STEP from the page; OpenCASCADE reads it back as the same surface", async (t) => {
  const readback = process.env.SFIT_STEP_READBACK;
  const st = (await api.get("/api/state")).json;
  if (!readback || !st.exports.includes("step")) {
    t.skip("this build has no STEP writer (OpenCASCADE): nothing to read back");
    return;
  }
  await page.select("#format", "step");
  await page.click("#exportBeside");
  await page.waitForFunction(() => /wrote .*\.step/.test(document.getElementById("message").textContent),
    { timeout: 30000 });
  const step = (await page.$eval("#message", (e) => e.textContent)).replace(/^wrote /, "");
  const json = (await api.post("/api/export", { format: "json" })).json.path;
  const r = JSON.parse(execFileSync(readback, [step, json], { encoding: "utf8" }));
  assert.equal(r.faces, 1);
  assert.equal(r.valid, true);
  assert.deepEqual(r.degree, st.report.degree);
  assert.deepEqual(r.poles, st.report.control_points);
  assert.ok(r.max_relative_deviation < 1e-9, `STEP differs by ${r.max_relative_deviation} of the diagonal`);
});

test("screenshot of the editor", async () => {
  await page.click("#net");  // off again
  await page.select("#mode", "deviation");
  await page.evaluate(() => window.sfitEditor.nextFrame());
  const s = await page.evaluate(() => window.sfitEditor.screenOf(5, 4));
  await page.mouse.move(s.x, s.y);
  await page.mouse.down();
  await page.mouse.up();
  await page.evaluate(() => window.sfitEditor.nextFrame());
  const path = join(OUT, "editor.png");
  await page.screenshot({ path });
  console.log(`screenshot: ${path}`);
  assert.deepEqual(errors, []);
});
