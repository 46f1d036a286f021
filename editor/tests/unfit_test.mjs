// A file that does not fit at its T opens in the editor, in Debian's Chromium (headless,
// software GL) with real mouse and keyboard events: the best surface found is shown with the
// reason, an edit that makes it fit brings the normal state back; a final surface that misses
// T (here: held counts after a long drag) has its failing points ringed and listed, and a
// click on one in the list selects it (the screenshot editor-unfit.png of docs/editor.md).
import { test, before, after } from "node:test";
import assert from "node:assert/strict";
import { join, dirname } from "node:path";
import { fileURLToPath } from "node:url";
import { skipUnlessChromium, loadPuppeteer, startEditor, launch, openPage } from "./browser.mjs";
import { client } from "./api.mjs";
import { sleep, settledAt } from "./page_helpers.mjs";

skipUnlessChromium();
const SFIT = process.env.SFIT_CLI;
const EXAMPLES = process.env.SFIT_EXAMPLES;
const OUT = process.env.SFIT_OUT || ".";
if (!SFIT || !EXAMPLES) throw new Error("set SFIT_CLI and SFIT_EXAMPLES (CTest does)");
const puppeteer = await loadPuppeteer();
// Degree 20 at T = 0: the count search finds no surface (sfit fit exits 7 on it).
const UNFIT = join(dirname(fileURLToPath(import.meta.url)), "../../tests/bad_input/degree20_interpolation_not_met.rows");

let browser;
before(async () => { browser = await launch(puppeteer); });
after(async () => { if (browser) await browser.close(); });

const settled = settledAt;
const version = (page) => page.evaluate(() => window.sfitEditor.state.version);
async function typeInto(page, id, text) {
  await page.click(`#${id}`, { clickCount: 3 });
  await page.keyboard.press("Backspace");
  await page.keyboard.type(text);
  await page.keyboard.press("Enter");
}

test("a file with no surface within its T opens with the best found; an edit that fits it brings the normal state", async () => {
  const ed = await startEditor(SFIT, UNFIT, ["--degree", "20", "--tol", "0"]);
  try {
    const api = client(ed);
    const st = (await api.get("/api/state")).json;
    assert.match(st.best_effort || "", /re-representation cannot hold the tolerance.*shown: /, "the reason and what is shown");
    assert.deepEqual(st.options.degree, [20, 20], "the options stay as asked");
    assert.match(ed.stderr(), /sfit: warning: no surface within T \(re-representation .*\); the editor shows the best found/);
    assert.equal(st.final, true);
    const errors = [];
    const page = await openPage(browser, ed.url, errors);
    const status = await page.$eval("#status", (e) => e.textContent);
    assert.match(status, /no surface within T found \(re-representation cannot hold.*\): the best found is shown/);
    assert.equal(await page.$eval("#status", (e) => e.className), "status bad");
    // Fix it: the degree typed back to 3 in both directions.
    for (const id of ["degU", "degV"]) {
      const v = await version(page);
      await page.click(`#${id}`, { clickCount: 3 });
      await page.keyboard.type("3");
      await page.keyboard.press("Tab");  // the change event
      await settled(page, v + 1);
    }
    const fixed = (await api.get("/api/state")).json;
    assert.deepEqual(fixed.options.degree, [3, 3]);
    assert.equal(fixed.best_effort, null, "the full search's surface again");
    assert.equal(fixed.report.within_tolerance, true);
    assert.match(await page.$eval("#status", (e) => e.textContent), /final surface: fewest control points/);
    // Undo: the best effort again, with its reason.
    let v = await version(page);
    await page.click("#undo");
    await settled(page, v + 1);
    v = await version(page);
    await page.click("#undo");
    await settled(page, v + 1);
    assert.match((await api.get("/api/state")).json.best_effort || "", /re-representation/);
    assert.match(await page.$eval("#status", (e) => e.textContent), /no surface within T found/);
    assert.deepEqual(errors, []);
  } finally {
    await ed.stop();
  }
});

test("a final surface over T: the failing points ringed and listed; a click in the list selects one; released, the fit holds T", async () => {
  const ed = await startEditor(SFIT, join(EXAMPLES, "table1_synthetic.rows"));
  try {
    const api = client(ed);
    const errors = [];
    const page = await openPage(browser, ed.url, errors);
    let v = await version(page);
    await page.click("#hold");
    await settled(page, v + 1);
    // Drag a point far along z (the held counts cannot follow it within T).
    await page.select("#axis", "z");
    const s = await page.evaluate(() => window.sfitEditor.screenOf(8, 20));
    await page.mouse.click(s.x, s.y);
    await page.waitForFunction(() => window.sfitEditor.selected() !== null);
    v = await version(page);
    await page.mouse.move(s.x, s.y);
    await page.mouse.down();
    for (let k = 1; k <= 12; k++) { await page.mouse.move(s.x, s.y - 20 * k); await sleep(15); }
    await page.mouse.up();
    await settled(page, v + 1);
    const st = (await api.get("/api/state")).json;
    assert.equal(st.report.within_tolerance, false, "held, the dragged point is out of reach");
    const over = [];
    st.point_deviation.forEach((r, j) => r.forEach((x, i) => { if (x > 1) over.push([j, i, x]); }));
    assert.ok(over.length > 0);
    await page.waitForFunction(() => document.getElementById("failing").style.display === "block", { timeout: 10000 });
    const listed = await page.$$eval("#failing .failpoint", (bs) => bs.map((b) => [Number(b.dataset.row), Number(b.dataset.index)]));
    over.sort((a, b) => b[2] - a[2]);
    assert.deepEqual(listed, over.slice(0, 12).map(([j, i]) => [j, i]), "the points over T, worst first");
    assert.match(await page.$eval("#failing", (e) => e.textContent), new RegExp(`${over.length} points? over T`));
    assert.match(await page.$eval("#status", (e) => e.textContent), new RegExp(`NOT within T at ${over.length} points`));
    const last = listed[listed.length - 1];
    // The button's own click (not a mouse click at its place on the screen: a full ctest -j2 run
    // once selected the dragged point instead, as if the click had landed on the canvas).
    await page.$eval(`#failing .failpoint[data-row="${last[0]}"][data-index="${last[1]}"]`, (b) => b.click());
    assert.deepEqual(await page.evaluate(() => window.sfitEditor.selected()), { row: last[0], index: last[1] });
    assert.equal(await page.$eval("#selName", (e) => e.textContent), `row ${last[0]}, point ${last[1]}`);
    await page.select("#mode", "deviation");
    await page.evaluate(() => window.sfitEditor.nextFrame());
    await page.screenshot({ path: join(OUT, "editor-unfit.png") });
    // Release the hold: the search's surface, within T, and no list.
    v = await version(page);
    await page.click("#hold");
    await settled(page, v + 1);
    assert.equal((await api.get("/api/state")).json.report.within_tolerance, true);
    assert.equal(await page.$eval("#failing", (e) => e.style.display), "none");
    assert.deepEqual(errors, []);
  } finally {
    await ed.stop();
  }
});
