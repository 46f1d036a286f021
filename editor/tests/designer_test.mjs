// The editor as a designer uses it, in Debian's Chromium (headless, software GL) with real
// mouse and keyboard events (puppeteer-core): fields refused in place, the page and the server
// agreeing after every operation, the hold of the surface's shape, near-point warnings, a
// second editor of the same file (read-only), a tab closed mid-drag (the session ends at a full
// fit), legends, typed T, closed rows offered on open. (drag_test.mjs: the drags.)
import { test, before, after } from "node:test";
import assert from "node:assert/strict";
import { existsSync, readFileSync } from "node:fs";
import { join } from "node:path";
import { startEditor, openPage } from "./browser.mjs";
import { client } from "./api.mjs";
import { openEditor, pageHelpers, diagonalOf, sleep } from "./page_helpers.mjs";

const SFIT = process.env.SFIT_CLI;
const EXAMPLES = process.env.SFIT_EXAMPLES;
const OUT = process.env.SFIT_OUT || ".";
if (!SFIT || !EXAMPLES) throw new Error("set SFIT_CLI and SFIT_EXAMPLES (CTest does)");
const HULL = join(EXAMPLES, "ship_px121_stations.rows");

let ctx, ed, api, browser, page, initial, diag, errors;
before(async () => {
  ctx = await openEditor(SFIT, HULL);
  ({ ed, api, browser, page, errors } = ctx);
  initial = (await api.get("/api/state")).json;
  diag = diagonalOf(initial.rows);
});
after(async () => { if (ctx) await ctx.close(); });
const { idle, settled, version, consistent, deselect, clickPoint, drag, typeInto } = pageHelpers(() => ctx);
const close = (a, b, tol) => Math.abs(a - b) <= tol;

test("an empty or invalid coordinate field is refused in place, never read as 0", async () => {
  await clickPoint(5, 4);
  const v0 = await version();
  const before = (await api.get("/api/state")).json;
  for (const text of ["", "abc", "1e", " "]) {
    await typeInto("pz", text);
    await page.click("#setPoint");
    await sleep(100);
    const f = await page.$eval("#pz", (e) => ({ invalid: e.classList.contains("invalid"), aria: e.getAttribute("aria-invalid") }));
    assert.equal(f.invalid, true, `'${text}' is marked invalid in place`);
    assert.equal(f.aria, "true");
    assert.match(await page.$eval("#message", (e) => e.textContent), /z: is empty or not a number.*nothing was changed/);
  }
  const st = (await api.get("/api/state")).json;
  assert.equal(st.version, before.version, "nothing was sent");
  assert.deepEqual(st.rows, before.rows);
  assert.equal(await version(), v0);
  await typeInto("pz", "3.5");
  await page.click("#setPoint");
  await settled(v0 + 1);
  const after = await consistent("typed z");
  assert.equal(after.rows[5][4][2], 3.5);
  assert.deepEqual(after.rows[5][4].slice(0, 2), before.rows[5][4].slice(0, 2));
});

test("deleting the selected row: no JavaScript error, the page and the server agree; undo too", async () => {
  const st0 = await consistent("before");
  await clickPoint(3, 2);
  const v = await version();
  await page.click("#delRow");
  await settled(v + 1);
  const st = await consistent("after deleting row 3");
  assert.equal(st.rows.length, st0.rows.length - 1);
  assert.equal(await page.evaluate(() => window.sfitEditor.selected()), null, "the selection went with its row");
  await deselect();
  await page.keyboard.down("Control"); await page.keyboard.press("z"); await page.keyboard.up("Control");
  await settled(v + 2);
  const back = await consistent("after undo");
  assert.deepEqual(back.rows, st0.rows);
  // Delete the last row's point while it is selected, then the last row itself.
  await clickPoint(st0.rows.length - 1, 0);
  const v2 = await version();
  await page.click("#delPoint");
  await settled(v2 + 1);
  await consistent("after deleting the selected point");
  await clickPoint(st0.rows.length - 1, 0);
  await page.click("#delRow");
  await settled(v2 + 2);
  await consistent("after deleting the last row");
  for (let k = 0; k < 2; k++) {
    const vv = await version();
    await page.click("#undo");
    await settled(vv + 1);
    await consistent(`after undo ${k}`);
  }
  assert.deepEqual((await api.get("/api/state")).json.rows, st0.rows);
});

test("hold the shape: counts and rule stay through a drag; the search's answer is shown; released, the search takes over", async () => {
  const v = await version();
  await page.click("#hold");
  await settled(v + 1);
  let st = await consistent("after hold");
  assert.equal(st.options.hold, true);
  const counts = st.report.control_points, rule = st.report.parameters;
  const s = await clickPoint(5, 5);
  const v1 = await version();
  await drag(s, 60, -70, { steps: 15 });
  await settled(v1 + 1);
  await page.waitForFunction(() => /full search now gives/.test(document.getElementById("counts").textContent), { timeout: 60000 });
  st = await consistent("after the held drag");
  assert.deepEqual(st.report.control_points, counts, "the counts were held");
  assert.equal(st.report.parameters, rule, "the rule was held");
  const search = await page.evaluate(() => window.sfitEditor.search);
  assert.ok(search && search.counts.length === 2);
  // before -> after: the held counts and rule, and what the search would give instead.
  assert.match(await page.$eval("#counts", (e) => e.textContent), new RegExp(`^held at ${counts[0]} × ${counts[1]} \\(${rule}\\); ` +
    `the full search now gives ${search.counts[0]} × ${search.counts[1]} \\(${search.parameters}`));
  const v2 = await version();
  await page.click("#hold");
  await settled(v2 + 1);
  st = await consistent("after releasing the hold");
  assert.equal(st.options.hold, false);
  assert.equal(st.report.within_tolerance, true, "released: the search's surface, within T");
  const countsText = await page.$eval("#counts", (e) => e.textContent);
  if (st.report.control_points.join() !== counts.join())
    assert.match(countsText, new RegExp(`${counts[0]} × ${counts[1]} -> ${st.report.control_points[0]} × ${st.report.control_points[1]}`));
});

test("a point typed next to its neighbour is warned about", async () => {
  const st0 = (await api.get("/api/state")).json;
  await clickPoint(4, 3);
  const q = st0.rows[4][2].map((x, a) => (a === 1 ? x + 1e-4 * diag : x));
  for (const [id, x] of [["px", q[0]], ["py", q[1]], ["pz", q[2]]]) await typeInto(id, String(x));
  const v = await version();
  await page.click("#setPoint");
  await settled(v + 1);
  await page.waitForFunction(() => /row 4, point 3 is .* from row 4, point 2/.test(document.getElementById("warn").textContent), { timeout: 30000 });
  await consistent("after the typed neighbour");
  const v2 = await version();
  await page.click("#undo");
  await settled(v2 + 1);
});

test("typed T: a number, with a unit or % of the diagonal; nonsense refused in place", async () => {
  const units = (await api.get("/api/state")).json.units;
  let v = await version();
  await typeInto("tolIn", "0.1%");
  await page.keyboard.press("Enter");
  await settled(v + 1);
  let st = await consistent("after T = 0.1%");
  assert.ok(close(st.options.tolerance[0], 1e-3 * diag, 1e-9 * diag), `T ${st.options.tolerance[0]}`);
  if (units === "mm") {
    v = await version();
    await typeInto("tolIn", "0.02 cm");
    await page.keyboard.press("Enter");
    await settled(v + 1);
    st = await consistent("after T = 0.02 cm");
    assert.ok(close(st.options.tolerance[0], 0.2, 1e-12));
  }
  v = await version();
  await typeInto("tolIn", "abc");
  await page.keyboard.press("Enter");
  await sleep(200);
  assert.equal(await page.$eval("#tolIn", (e) => e.classList.contains("invalid")), true);
  assert.equal(await version(), v, "nothing sent");
  await page.click("#undo");
  await settled(v + 1);
  if (units === "mm") { await page.click("#undo"); await settled(v + 2); }
  assert.deepEqual((await api.get("/api/state")).json.options.tolerance, initial.options.tolerance);
});

test("the knots menu: adaptive knots asked for from the page, reported by the server, undone", async () => {
  const choices = await page.$$eval("#knots option", (os) => os.map((o) => o.textContent));
  assert.deepEqual(choices, ["corners", "uniform", "adaptive"], "the choices are the option table's");
  const st0 = await consistent("before the knots");
  assert.equal(await page.$eval("#knots", (e) => e.value), "corners");
  const v = await version();
  await page.select("#knots", "adaptive");
  await settled(v + 1);
  const st = await consistent("adaptive knots");
  assert.equal(st.options.knots, "adaptive");
  assert.equal(st.report.within_tolerance, true);
  const n = (r) => r.control_points[0] * r.control_points[1];
  assert.ok(n(st.report) <= n(st0.report), `never more control points: ${n(st.report)} vs ${n(st0.report)}`);
  assert.equal(st.report.knots, n(st.report) < n(st0.report) ? "adaptive" : "uniform");
  await page.click("#undo");
  await settled(v + 2);
  const back = await consistent("undone");
  assert.equal(back.options.knots, "corners");
  assert.equal(await page.$eval("#knots", (e) => e.value), "corners", "the menu follows the undo");
});

test("legends for deviation and curvature; zebra stripe controls; the control net's points can be looked at", async () => {
  await page.select("#mode", "deviation");
  await page.evaluate(() => window.sfitEditor.nextFrame());
  assert.match(await page.$eval("#legend", (e) => e.textContent), /deviation.*T =/);
  await page.select("#mode", "curvature");
  await page.evaluate(() => window.sfitEditor.nextFrame());
  assert.match(await page.$eval("#legend", (e) => e.textContent), /mean curvature/);
  await page.select("#mode", "zebra");
  await page.$eval("#stripes", (e) => { e.value = "20"; e.dispatchEvent(new Event("input")); });
  await page.select("#stripeDir", "z");
  await page.evaluate(() => window.sfitEditor.nextFrame());
  await page.select("#mode", "shaded");
  await page.click("#net");
  await page.evaluate(() => window.sfitEditor.nextFrame());
  await deselect();
  const target = await page.evaluate(() => {
    const h = window.sfitEditor;
    for (const r of h.state.surface.control_points)
      for (const p of r) {
        const s = h.screenOfPoint(p);
        const c = document.querySelector("#view canvas").getBoundingClientRect();
        if (s.x > c.left + 20 && s.x < c.right - 20 && s.y > c.top + 40 && s.y < c.bottom - 60 && !h.pick(s.x, s.y)) return s;
      }
    return null;
  });
  assert.ok(target, "a control point away from the data points");
  await page.mouse.click(target.x, target.y);
  await page.waitForFunction(() => /control point \(\d+, \d+\)/.test(document.getElementById("message").textContent), { timeout: 30000 });
  await page.click("#net");
  assert.deepEqual(errors, []);
});

test("a second editor of the same file opens read-only; saves never cross", async () => {
  const ed2 = await startEditor(SFIT, ed.input, [], { inPlace: true });
  try {
    const api2 = client(ed2);
    const st2 = (await api2.get("/api/state")).json;
    assert.equal(st2.read_only, true);
    assert.match(st2.lock, /another sfit edit \(process \d+\) is editing this file/);
    const errors2 = [];
    const page2 = await openPage(browser, ed2.url, errors2);
    assert.match(await page2.$eval("#lock", (e) => e.textContent), /read-only/);
    assert.equal(await page2.$eval("#save", (e) => e.disabled), true, "save is off in the second editor");
    const r = await api2.post("/api/save", {});
    assert.equal(r.status, 400);
    assert.match(r.json.error, /read-only/);
    assert.equal(existsSync(ed.input + ".bak"), false, "the second editor wrote no backup");
    await page2.close();
    assert.deepEqual(errors2, []);
  } finally {
    await ed2.stop();
  }
  assert.equal(existsSync(ed.input + ".sfit-lock"), true, "the first editor keeps its lock");
  const original = readFileSync(ed.input, "utf8");
  const r1 = await api.post("/api/save", {});
  assert.equal(r1.status, 200, "the first editor saves");
  assert.equal(readFileSync(ed.input + ".bak", "utf8"), original);
});

test("a tab closed mid-drag leaves the session at a full fit", async () => {
  const errors3 = [];
  const page3 = await openPage(browser, ed.url, errors3);
  const st0 = (await api.get("/api/state")).json;
  await page3.evaluate(() => { window.sfitEditor.restMs = 1e6; });  // no rest: the drag stays quick
  const s = await page3.evaluate(() => window.sfitEditor.screenOf(5, 3));
  await page3.mouse.click(s.x, s.y);
  await page3.waitForFunction(() => window.sfitEditor.selected() !== null);
  await page3.mouse.move(s.x, s.y);
  await page3.mouse.down();
  for (let k = 1; k <= 8; k++) { await page3.mouse.move(s.x + 4 * k, s.y - 6 * k); await sleep(10); }
  const seen = await page3.waitForFunction(() => window.sfitEditor.state.dragging && !window.sfitEditor.state.final,
    { timeout: 30000 }).then(() => null, async () => page3.evaluate(() => JSON.stringify({
    drag: window.sfitEditor.dragging(), sel: window.sfitEditor.selected(), moves: window.sfitEditor.moves.length,
    st: [window.sfitEditor.state.version, window.sfitEditor.state.dragging, window.sfitEditor.state.final],
    msg: document.getElementById("message").textContent }))); 
  assert.equal(seen, null, "the page dragged (a quick refit shown)");
  // The page may draw the drag from its own prediction before a step reaches the server
  // (predict.js): the tab closes once the server is mid-drag too.
  const t1 = Date.now();
  while (!(await api.get("/api/state?rows=0")).json.dragging && Date.now() - t1 < 10000) await sleep(20);
  await page3.close();  // no pointerup, no "end"
  const t0 = Date.now();
  let st;
  do { await sleep(200); st = (await api.get("/api/state")).json; } while (st.dragging && Date.now() - t0 < 15000);
  assert.equal(st.dragging, false, "the server ended the drag");
  assert.equal(st.final, true, "the full fit");
  assert.equal(st.report.within_tolerance, true);
  assert.equal(st.undo, st0.undo + 1, "the drag is one undo step");
  assert.notDeepEqual(st.rows[5][3], st0.rows[5][3]);
  assert.deepEqual(errors3, []);
  // The first page catches up by itself (it asks for the version while idle).
  await page.waitForFunction((v) => window.sfitEditor.state.version === v, { timeout: 30000 }, st.version);
  await consistent("the first page after the other tab's drag");
});

test("closed rows are detected on open: the CLI's note, closed u in one click", async () => {
  const ed4 = await startEditor(SFIT, join(EXAMPLES, "d150_wing.rows"));
  try {
    const api4 = client(ed4);
    const st = (await api4.get("/api/state")).json;
    assert.equal(st.options.closed[0], false);
    assert.match(st.closed_hint || "", /ends of every row .* meet/);
    const errors4 = [];
    const page4 = await openPage(browser, ed4.url, errors4);
    assert.equal(await page4.$eval("#closedHint", (e) => e.style.display), "block");
    const v = await page4.evaluate(() => window.sfitEditor.state.version);
    await page4.click("#applyClosed");
    await settled(v + 1, page4);
    const st4 = await consistent("after closed u", page4, api4);
    assert.equal(st4.options.closed[0], true);
    assert.equal(await page4.$eval("#closedHint", (e) => e.style.display), "none");
    await page4.close();
    assert.deepEqual(errors4, []);
  } finally {
    await ed4.stop();
  }
});
