// Shared by the browser tests: one editor on a copy of a data set, Chromium with its page, and
// the helpers that drive the page with real mouse and keyboard events (puppeteer-core) and
// check that the page and the server agree.
import assert from "node:assert/strict";
import { skipUnlessChromium, loadPuppeteer, startEditor, launch, openPage } from "./browser.mjs";
import { client } from "./api.mjs";

export const sleep = (ms) => new Promise((r) => setTimeout(r, ms));

/// Waits until `page` shows the server's full fit of version `minVersion` or later, idle.
export const settledAt = (page, minVersion) => page.waitForFunction((v) => {
  const h = window.sfitEditor;
  return h.idle && h.state && h.state.version >= v && h.state.final && !h.state.dragging && h.state.rows;
}, { timeout: 60000 }, minVersion);

/// Starts `sfit edit` on a copy of `rows` (with `extra` arguments), Chromium and the page.
/// Resolves with {ed, api, browser, page, errors, close()}; skips (exit 77) without Chromium.
export async function openEditor(sfit, rows, extra = []) {
  skipUnlessChromium();
  const puppeteer = await loadPuppeteer();
  const ed = await startEditor(sfit, rows, extra);
  const errors = [];
  let browser;
  try {
    browser = await launch(puppeteer);
    const page = await openPage(browser, ed.url, errors);
    return { ed, api: client(ed), browser, page, errors,
      async close() { await browser.close(); await ed.stop(); } };
  } catch (e) {
    if (browser) await browser.close();
    await ed.stop();
    throw e;
  }
}

/// The page helpers, bound lazily to `ctx()` = {page, api, errors} (set once the test's
/// before() has run); each takes another page (and client) where a test has two.
export function pageHelpers(ctx) {
  const idle = (p = ctx().page) => p.waitForFunction(() => window.sfitEditor.idle, { timeout: 60000 });
  const settled = (minVersion, p = ctx().page) => settledAt(p, minVersion);
  const version = (p = ctx().page) => p.evaluate(() => window.sfitEditor.state.version);

  /// The page and the server agree: the rows shown are the server's, the version, the counts
  /// and the number of rows and points in the report; the selection names a point that exists.
  async function consistent(what, p = ctx().page, a = ctx().api) {
    await idle(p);
    const st = (await a.get("/api/state")).json;
    const shown = await p.evaluate(() => ({
      rows: window.sfitEditor.rows(), version: window.sfitEditor.state.version,
      report: document.getElementById("report").textContent, sel: window.sfitEditor.selected() }));
    assert.deepEqual(shown.rows, st.rows, `${what}: the page's rows are the server's`);
    assert.equal(shown.version, st.version, `${what}: the page shows the server's version`);
    assert.ok(shown.report.includes(`${st.report.points} in ${st.report.rows} rows`), `${what}: report ${shown.report}`);
    assert.ok(shown.report.includes(`${st.report.control_points[0]} × ${st.report.control_points[1]}`), `${what}: counts`);
    if (shown.sel) assert.ok(st.rows[shown.sel.row] && st.rows[shown.sel.row][shown.sel.index], `${what}: the selection exists`);
    assert.deepEqual(ctx().errors, [], `${what}: no JavaScript error`);
    return st;
  }

  async function deselect(p = ctx().page) {
    await p.evaluate(() => document.activeElement && document.activeElement.blur());
    await p.keyboard.press("Escape");
  }
  async function clickPoint(row, index, p = ctx().page) {
    await deselect(p);
    // As a user clicks what is shown: the page idle (no answer pending that redraws it) and
    // the frame after the last change of view or mode drawn.
    await idle(p);
    await p.evaluate(() => window.sfitEditor.nextFrame());
    const s = await p.evaluate((r, i) => window.sfitEditor.screenOf(r, i), row, index);
    await p.mouse.click(s.x, s.y);
    await p.waitForFunction((r, i) => { const s = window.sfitEditor.selected(); return s && s.row === r && s.index === i; },
      { timeout: 30000 }, row, index);
    return s;
  }
  async function drag(s, dx, dy, { steps = 10, up = true, during } = {}, p = ctx().page) {
    await p.mouse.move(s.x, s.y);
    await p.mouse.down();
    for (let k = 1; k <= steps; k++) {
      await p.mouse.move(s.x + (dx * k) / steps, s.y + (dy * k) / steps);
      await sleep(15);
    }
    if (during) await during();
    if (up) await p.mouse.up();
  }
  async function typeInto(id, text, p = ctx().page) {
    await p.click(`#${id}`, { clickCount: 3 });
    await p.keyboard.press("Backspace");
    if (text) await p.keyboard.type(text);
  }
  return { idle, settled, version, consistent, deselect, clickPoint, drag, typeInto };
}

/// The diagonal of the rows' bounding box.
export function diagonalOf(rows) {
  const r = rows.flat(), lo = [0, 1, 2].map((a) => Math.min(...r.map((p) => p[a])));
  const hi = [0, 1, 2].map((a) => Math.max(...r.map((p) => p[a])));
  return Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
}
