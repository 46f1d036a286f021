// Dragging as a designer does, in Debian's Chromium (headless, software GL) with real mouse and
// keyboard events (puppeteer-core): select, then drag (a drag elsewhere orbits, F fits the
// view), the row-plane constraint drawn with the fields following, along an axis, Esc cancels,
// Tab locks the direction, arrow-key nudges. Writes the screenshot of a constrained drag
// (editor-drag.png) next to the one of browser_test.mjs. (designer_test.mjs: the rest.)
import { test, before, after } from "node:test";
import assert from "node:assert/strict";
import { join } from "node:path";
import { openEditor, pageHelpers, diagonalOf, sleep } from "./page_helpers.mjs";

const SFIT = process.env.SFIT_CLI;
const EXAMPLES = process.env.SFIT_EXAMPLES;
const OUT = process.env.SFIT_OUT || ".";
if (!SFIT || !EXAMPLES) throw new Error("set SFIT_CLI and SFIT_EXAMPLES (CTest does)");
const HULL = join(EXAMPLES, "ship_px121_stations.rows");

let ctx, api, page, initial, diag, errors;
before(async () => {
  ctx = await openEditor(SFIT, HULL);
  ({ api, page, errors } = ctx);
  initial = (await api.get("/api/state")).json;
  diag = diagonalOf(initial.rows);
});
after(async () => { if (ctx) await ctx.close(); });
const { idle, settled, version, consistent, deselect, clickPoint, drag, typeInto } = pageHelpers(() => ctx);
const close = (a, b, tol) => Math.abs(a - b) <= tol;

test("select, then drag: a drag off the selected point orbits and moves nothing; F fits the view", async () => {
  await deselect();
  const st0 = (await api.get("/api/state")).json;
  const cam0 = await page.evaluate(() => window.sfitEditor.camera());
  const s = await page.evaluate(() => window.sfitEditor.screenOf(5, 4));
  await drag(s, 80, -30);  // on a point that is not selected: an orbit
  await idle();
  const cam1 = await page.evaluate(() => window.sfitEditor.camera());
  assert.notDeepEqual(cam1.position, cam0.position, "the view orbited");
  const st1 = (await api.get("/api/state")).json;
  assert.equal(st1.version, st0.version, "no edit was sent");
  assert.deepEqual(st1.rows, st0.rows);
  // Zoom in with the wheel far off-centre, then F: every point back in view.
  await page.mouse.move(200, 150);
  for (let k = 0; k < 8; k++) await page.mouse.wheel({ deltaY: -400 });
  await sleep(100);
  await page.keyboard.press("f");
  await page.evaluate(() => window.sfitEditor.nextFrame());
  const inView = await page.evaluate(() => {
    const c = document.querySelector("#view canvas").getBoundingClientRect();
    return window.sfitEditor.rows().every((r, j) => r.every((p, i) => {
      const s = window.sfitEditor.screenOf(j, i);
      return s.x >= c.left && s.x <= c.right && s.y >= c.top && s.y <= c.bottom;
    }));
  });
  assert.ok(inView, "F shows every point");
  await consistent("after orbit and F");
});

test("the default drag keeps a station's point in its station plane; the plane is drawn, the fields follow", async () => {
  const st0 = (await api.get("/api/state")).json;
  assert.equal(await page.$eval("#axis", (e) => e.value), "row");
  const c = await page.evaluate(() => window.sfitEditor.constraintOf(5, 4));
  assert.equal(c.kind, "plane");
  assert.deepEqual(c.v.map(Math.abs), [1, 0, 0], `the best plane of a station is x = const: normal ${c.v}`);
  await page.select("#mode", "deviation");
  await page.evaluate(() => window.sfitEditor.viewFrom([0.9, -0.6, 0.5]));  // the station plane at an angle
  const s = await clickPoint(5, 4);
  const v = await version();
  let during;
  await drag(s, 30, -35, {
    during: async () => {
      await page.evaluate(() => window.sfitEditor.nextFrame());
      during = await page.evaluate(() => ({
        constraint: window.sfitEditor.constraint(), p: window.sfitEditor.rows()[5][4],
        fields: ["px", "py", "pz"].map((id) => Number(document.getElementById(id).value)) }));
      await page.screenshot({ path: join(OUT, "editor-drag.png") });
    },
  });
  assert.equal(during.constraint, "constraint-plane", "the plane is drawn during the drag");
  assert.deepEqual(during.fields, during.p, "the coordinate fields follow the drag");
  await settled(v + 1);
  const st = await consistent("after the row-plane drag");
  const p0 = st0.rows[5][4], p = st.rows[5][4];
  assert.equal(p[0], p0[0], `x stays on the station exactly: ${p0[0]} -> ${p[0]}`);
  assert.ok(Math.hypot(p[1] - p0[1], p[2] - p0[2]) > 1e-3 * diag, "the point moved in the plane");
  assert.equal(await page.evaluate(() => window.sfitEditor.constraint()), null, "the constraint is gone after the drag");
});

test("along z moves z only; Esc cancels a drag; Tab locks the direction", async () => {
  await page.select("#axis", "z");
  let st0 = (await api.get("/api/state")).json;
  let s = await clickPoint(6, 3);
  let v = await version();
  await drag(s, 10, -40, { during: async () => assert.equal(await page.evaluate(() => window.sfitEditor.constraint()), "constraint-line") });
  await settled(v + 1);
  let st = await consistent("after the z drag");
  let p0 = st0.rows[6][3], p = st.rows[6][3];
  assert.ok(p[0] === p0[0] && p[1] === p0[1], `only z changed: ${p0} -> ${p}`);
  assert.ok(Math.abs(p[2] - p0[2]) > 1e-3 * diag);

  // Esc mid-drag: the point back where it was, no undo step.
  st0 = st;
  v = await version();
  s = await page.evaluate(() => window.sfitEditor.screenOf(6, 3));
  await drag(s, 0, -50, { up: false });
  await page.keyboard.press("Escape");
  await page.mouse.up();
  await idle();
  await page.waitForFunction(() => !window.sfitEditor.state.dragging, { timeout: 30000 });
  st = await consistent("after Esc");
  assert.deepEqual(st.rows, st0.rows, "Esc put the point back");
  assert.equal(st.undo, st0.undo, "a cancelled drag is no undo step");
  assert.equal(st.dragging, false);

  // Tab: the direction moved so far is locked; a sideways hand keeps to it.
  await page.select("#axis", "row");
  s = await clickPoint(6, 3);
  st0 = (await api.get("/api/state")).json;
  v = await version();
  let first;
  await drag(s, 25, 0, { steps: 5, up: false });
  first = await page.evaluate(() => window.sfitEditor.rows()[6][3]);
  await page.keyboard.press("Tab");
  assert.deepEqual(await page.evaluate(() => window.sfitEditor.dragging()), { row: 6, index: 3, locked: true });
  for (let k = 1; k <= 5; k++) { await page.mouse.move(s.x + 25 + 8 * k, s.y - 12 * k); await sleep(15); }
  await page.mouse.up();
  await settled(v + 1);
  st = await consistent("after the locked drag");
  p0 = st0.rows[6][3]; p = st.rows[6][3];
  const d1 = first.map((x, a) => x - p0[a]), d = p.map((x, a) => x - p0[a]);
  const cross = [d1[1] * d[2] - d1[2] * d[1], d1[2] * d[0] - d1[0] * d[2], d1[0] * d[1] - d1[1] * d[0]];
  assert.ok(Math.hypot(...d) > Math.hypot(...d1) * 1.05, "the locked drag went on");
  assert.ok(Math.hypot(...cross) <= 1e-6 * Math.hypot(...d1) * Math.hypot(...d), `the drag kept the locked direction: ${d1} / ${d}`);
});

test("arrow keys nudge by the step: Shift 10x, Alt 0.1x", async () => {
  await page.select("#axis", "z");
  await clickPoint(7, 2);
  await typeInto("step", "0.5");
  await page.evaluate(() => document.activeElement.blur());
  let z = (await api.get("/api/state")).json.rows[7][2][2];
  for (const [mods, key, dz] of [[[], "ArrowUp", 0.5], [["Shift"], "ArrowUp", 5], [["Alt"], "ArrowDown", -0.05]]) {
    const v = await version();
    for (const m of mods) await page.keyboard.down(m);
    await page.keyboard.press(key);
    for (const m of mods) await page.keyboard.up(m);
    await settled(v + 1);
    const st = await consistent(`after ${mods.join("+")} ${key}`);
    assert.ok(close(st.rows[7][2][2] - z, dz, 1e-9 * diag), `${key}: z moved by ${st.rows[7][2][2] - z}, not ${dz}`);
    z = st.rows[7][2][2];
  }
  await page.select("#axis", "row");
});
