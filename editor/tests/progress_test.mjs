// A full search in the editor, in Debian's Chromium (headless, software GL) with real mouse
// events on 10^4 points: its progress is shown while it runs (phase, pairs tried, best so
// far), and when the hand moves again during the search at rest, the server drops it
// (FitOptions::cancel: its log and GET /api/progress say so) and the page never shows that
// stale surface; the release ends at the full fit.
import { test, before, after } from "node:test";
import assert from "node:assert/strict";
import { writeFileSync, mkdtempSync, rmSync } from "node:fs";
import { tmpdir } from "node:os";
import { join } from "node:path";
import { skipUnlessChromium, loadPuppeteer, startEditor, launch, openPage } from "./browser.mjs";
import { client } from "./api.mjs";
import { sleep } from "./page_helpers.mjs";

skipUnlessChromium();
const SFIT = process.env.SFIT_CLI;
if (!SFIT) throw new Error("set SFIT_CLI (CTest does)");
const puppeteer = await loadPuppeteer();

// 100 x 100 points of a terrain (bench/synthetic.h's): a full search of a second or more.
const M = 100, N = 100;
const terrain = (s, t) => [100 * s, 100 * t,
  10 * Math.sin(3 * s) * Math.cos(2 * t) + 5 * s * t * t + 0.5 * Math.sin(17 * s + 11 * t)];
const dir = mkdtempSync(join(tmpdir(), "sfit-progress-test-"));
const file = join(dir, "grid.rows");
let text = "";
for (let j = 0; j < M; j++) {
  for (let k = 0; k < N; k++) text += terrain(k / (N - 1), j / (M - 1)).join(" ") + "\n";
  text += "\n";
}
writeFileSync(file, text);

let ed, api, browser, page;
const errors = [];
before(async () => {
  ed = await startEditor(SFIT, file);
  api = client(ed);
  browser = await launch(puppeteer);
  page = await openPage(browser, ed.url, errors);
});
after(async () => {
  if (browser) await browser.close();
  if (ed) await ed.stop();
  rmSync(dir, { recursive: true, force: true });
});

test("a drag during the full search at rest drops it; its progress was shown; no stale surface", async () => {
  const st0 = (await api.get("/api/state")).json;
  await page.select("#axis", "z");
  const s = await page.evaluate(() => window.sfitEditor.screenOf(50, 50));
  await page.mouse.click(s.x, s.y);
  await page.waitForFunction(() => window.sfitEditor.selected() !== null);
  await page.evaluate(() => {
    const f = window.fetch;
    window.sentLog = [];
    window.fetch = (u, o) => { window.sentLog.push(`${performance.now().toFixed(0)} ${u} ${o && o.body}`); return f(u, o); };
  });
  await page.evaluate(() => { window.sfitEditor.restMs = 1e6; });  // no rest while the hand moves
  await page.mouse.move(s.x, s.y);
  await page.mouse.down();
  for (let k = 1; k <= 5; k++) { await page.mouse.move(s.x, s.y - 4 * k); await sleep(20); }
  await page.waitForFunction(() => window.sfitEditor.idle || window.sfitEditor.state.dragging, { timeout: 30000 });
  await page.evaluate(() => { window.sfitEditor.restMs = 100; });
  await page.mouse.move(s.x, s.y - 21);
  // The hand rests: the full search starts; its progress shows on the page.
  await page.waitForFunction(() => document.getElementById("progress").style.display === "block" &&
    /full search: .*pairs tried/.test(document.getElementById("progress").textContent), { timeout: 30000 });
  const during = (await api.get("/api/progress")).json;
  assert.equal(during.running, true, "the server says a search runs");
  const dropped0 = await page.evaluate(() => window.sfitEditor.dropped.length);
  // No new rest from here on: any full-search surface shown until the release is the stale one.
  const t = await page.evaluate(() => { window.sfitEditor.restMs = 1e6; return performance.now(); });
  // The hand moves again: the search is dropped.
  for (let k = 6; k <= 10; k++) { await page.mouse.move(s.x, s.y - 4 * k); await sleep(20); }
  // Until the page has seen the drop, the hand keeps moving a little: a drag step every 250
  // ms, so the server's drag watch (a drag without an edit for 5 s is ended: a page gone)
  // never takes this drag, which the test holds without rests, for an abandoned one, however
  // slow the machine.
  const wiggle = async (done, what) => {
    for (let k = 0, t0 = Date.now(); !(await done()); k++) {
      if (Date.now() - t0 > 30000) throw new Error(`timed out waiting for ${what}`);
      await page.mouse.move(s.x + (k % 2), s.y - 40);
      await sleep(250);
    }
  };
  await wiggle(() => page.evaluate((n) => window.sfitEditor.dropped.slice(n).some((d) => d.phase === "rest"), dropped0),
    "the page to see the dropped search");
  const after = (await api.get("/api/progress")).json;
  assert.ok(after.dropped > during.dropped, "the server counted the dropped search");
  assert.match(ed.stderr(), /the full search at rest dropped: a drag step came/);
  await page.mouse.move(s.x, s.y - 41);
  await sleep(300);
  const shown = await page.evaluate((t0) => window.sfitEditor.shown.filter((x) => x.t >= t0), t);
  assert.ok(shown.length > 0, "the drag went on");
  assert.deepEqual(shown.filter((x) => x.final), [], "no stale full-search surface was shown");
  await page.mouse.up();
  await page.waitForFunction(() => window.sfitEditor.idle && window.sfitEditor.state.final && !window.sfitEditor.state.dragging,
    { timeout: 120000 });
  const st = (await api.get("/api/state")).json;
  assert.equal(st.final, true);
  assert.equal(st.report.within_tolerance, true);
  assert.doesNotMatch(ed.stderr(), /a drag without an edit/, "the drag watch took the held drag for a page gone");
  if (st.undo !== st0.undo + 1) console.log(await page.evaluate(() => window.sentLog.join("\n")));
  assert.equal(st.undo, st0.undo + 1, `the drag is one undo step; the server said: ${ed.stderr()}`);
  assert.ok(st.rows[50][50][2] > st0.rows[50][50][2], "the point moved up");
  assert.equal(await page.evaluate(() => window.sfitEditor.state.version), st.version);
  assert.equal(await page.$eval("#progress", (e) => e.style.display), "none", "no progress once idle");
  assert.deepEqual(errors, []);
});
