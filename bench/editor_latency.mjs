// Latency of the editor in the browser: from the mouse event of a drag step to the frame
// that shows its refitted surface (drawn: the GPU's work done, by a WebGL2 fence; shown: the
// next animation frame, which hands the canvas to the compositor), on a 100 x 100 grid
// (10^4 points; bench/synthetic.h's terrain). Drag steps that a newer one
// overtook are skipped, not shown (latest wins), so only the shown ones have a latency of
// their own; every mouse event is also timed to the first frame showing it or a newer step.
// Reports p50/p95, the moves drawn and superseded, and the machine's load (1-minute load
// average, at the start and the end). Per drag also: the moves drawn from the page's own
// prediction of the refit (editor/js/predict.js) and the server's answers checked against it
// (the largest difference), the first five moves' latencies and the first one's split.
// A benchmark, not a test: nothing is asserted.
// `hold`: with the shape held (calm sculpting: the release's full search is shown, the counts
// and rule kept), so the second drag runs at the first fit's counts too; without it the
// release's full search replaces the surface (94 x 96 control points after the first drag).
// Usage (after building; editor/node_modules from `npm ci`):
//   SFIT_CLI=build/apps/sfit/sfit nice node bench/editor_latency.mjs [rows] [points per row] [hold]
import { writeFileSync, mkdtempSync, rmSync } from "node:fs";
import { tmpdir, loadavg, cpus } from "node:os";
import { join } from "node:path";
import { skipUnlessChromium, loadPuppeteer, startEditor, launch } from "../editor/tests/browser.mjs";

skipUnlessChromium();
const SFIT = process.env.SFIT_CLI;
if (!SFIT) throw new Error("set SFIT_CLI to the built sfit");
const M = Number(process.argv[2] || 100), N = Number(process.argv[3] || 100);
const hold = process.argv[4] === "hold";

const terrain = (s, t) => [100 * s, 100 * t,
  10 * Math.sin(3 * s) * Math.cos(2 * t) + 5 * s * t * t + 0.5 * Math.sin(17 * s + 11 * t)];
const dir = mkdtempSync(join(tmpdir(), "sfit-bench-"));
const file = join(dir, `grid${M}x${N}.rows`);
let text = "";
for (let j = 0; j < M; j++) {
  for (let k = 0; k < N; k++) text += terrain(k / (N - 1), j / (M - 1)).join(" ") + "\n";
  text += "\n";
}
writeFileSync(file, text);

const loadStart = loadavg()[0];
const compositing = process.env.SFIT_CHROMIUM_GL_COMPOSITING === "1" ? "GL compositing on SwiftShader" : "software compositing";
const ed = await startEditor(SFIT, file);
const puppeteer = await loadPuppeteer();
const browser = await launch(puppeteer);
const page = await browser.newPage();
await page.goto(ed.url);
await page.waitForFunction(() => window.sfitEditor && window.sfitEditor.ready, { timeout: 120000 });
if (hold) {
  await page.click("#hold");
  await page.waitForFunction(() => window.sfitEditor.idle && window.sfitEditor.state.options.hold, { timeout: 60000 });
}
await page.evaluate(() => window.sfitEditor.nextFrame());

const pctl = (xs, q) => {
  if (!xs.length) return NaN;
  const s = [...xs].sort((a, b) => a - b);
  return s[Math.min(s.length - 1, Math.floor(q * s.length))];
};
const results = [];
for (const [row, index] of [[Math.floor(M / 2), Math.floor(N / 2)], [Math.floor(M / 3), Math.floor(N / 4)]]) {
  await page.evaluate(() => { window.sfitEditor.latencies = []; window.sfitEditor.moves = []; window.sfitEditor.dropped = []; });
  const s = await page.evaluate((r, i) => window.sfitEditor.screenOf(r, i), row, index);
  await page.mouse.click(s.x, s.y);  // select, then drag
  await page.waitForFunction(() => window.sfitEditor.selected() !== null);
  await page.mouse.move(s.x, s.y);
  const frames0 = await page.evaluate(() => window.sfitEditor.frames);
  await page.evaluate(() => { window.sfitEditor.pressT = performance.now(); window.sfitEditor.influenceTimes = null; });
  await page.mouse.down();
  const moves = 60;
  for (let k = 1; k <= moves; k++) {
    await page.mouse.move(s.x + k, s.y - k);
    await new Promise((r) => setTimeout(r, 16));
  }
  const frames = (await page.evaluate(() => window.sfitEditor.frames)) - frames0;  // drawn during the drag
  await page.mouse.up();
  // The hand rests after the release until the full search is done (with the shape held, the
  // search shown beside the held surface).
  await page.waitForFunction(() => window.sfitEditor.idle && window.sfitEditor.state.final && !window.sfitEditor.state.dragging &&
    !window.sfitEditor.searching, { timeout: 120000 });
  await page.evaluate(() => window.sfitEditor.nextFrame());  // the last latency recorded
  const { lat, times, dropped, counts, checks, infl, inflServer } = await page.evaluate(() => ({ lat: window.sfitEditor.latencies,
    times: window.sfitEditor.moves, dropped: window.sfitEditor.dropped.length, counts: window.sfitEditor.state.report.control_points,
    checks: window.sfitEditor.predictionChecks.splice(0), infl: window.sfitEditor.influenceTimes, inflServer: window.sfitEditor.influence }));
  results.push({ moves, lat, times, dropped, counts, frames, checks, infl, inflServer });
}
// One latency per move: where a move was drawn twice (the server's answer, then the page's
// prediction once the influence arrived during the drag), the first frame.
for (const r of results) {
  const seen = new Set();
  r.lat = r.lat.filter((l) => l.phase !== "drag" || (!seen.has(l.t) && seen.add(l.t)));
}
const dragLat = results.flatMap((r) => r.lat.filter((l) => l.phase === "drag"));
results.forEach((r, k) => {
  const d = r.lat.filter((l) => l.phase === "drag");
  const m = (key) => pctl(d.map((l) => l[key]), 0.5).toFixed(1);
  console.log(`  drag ${k + 1} (counts at its start ${k ? results[k - 1].counts.join(" x ") : "of the first fit"}): ` +
    `p50 ${m("ms")} ms, p95 ${pctl(d.map((l) => l.ms), 0.95).toFixed(1)} ms; waiting ${m("wait")}, request ${m("request")} ms ` +
    `(refit ${m("server")}), drawing ${m("draw")}, to the next animation frame ${m("show")}; drawn ${d.length} of ${r.moves}; ` +
    `frames drawn during the drag ${r.frames}; predicted (drawn by the page) ${d.filter((l) => l.predicted).length}, ` +
    `server answers checked against their prediction ${r.checks.length} (largest difference ${Math.max(0, ...r.checks.map((c) => c.off)).toExponential(1)} ` +
    `of the control points' size); the first five moves shown ${d.slice().sort((a, b) => a.t - b.t).slice(0, 5).map((l) => l.ms.toFixed(0) + (l.predicted ? "" : " (server)")).join(", ")} ms (the first: waiting for the frame before ` +
    `${(d.slice().sort((a, b) => a.t - b.t)[0] || {}).slot?.toFixed(0)}, drawing ${(d.slice().sort((a, b) => a.t - b.t)[0] || {}).draw?.toFixed(0)}); influence asked ` +
    `${r.infl ? `${r.infl.asked.toFixed(0)} ms before the press, there ${r.infl.got.toFixed(0)} ms after it` : "never"}` +
    (r.inflServer ? ` (the last: ${r.inflServer.ms?.toFixed(0)} ms in all, the server ${(1000 * (r.inflServer.seconds || 0)).toFixed(0)} ms, ` +
      `its frozen refit factorised in ${(1000 * (r.inflServer.frozenSeconds || 0)).toFixed(0)} ms${r.inflServer.linear ? "" : `; not linear: ${r.inflServer.why}`})` : ""));
});
const drag = dragLat.map((l) => l.ms);
const fin = results.flatMap((r) => r.lat.filter((l) => l.final).map((l) => l.ms));
// Every mouse event, overtaken ones too: to the first frame showing its step or a newer one.
const every = results.flatMap((r) => {
  const shown = r.lat.filter((l) => l.phase === "drag").sort((a, b) => a.t - b.t);
  return r.times.flatMap((t) => {
    const f = shown.find((l) => l.t >= t);
    return f ? [f.t + f.ms - t] : [];
  });
});
const med = (k) => pctl(dragLat.map((l) => l[k]), 0.5);
console.log(`  median split: waiting for the previous request ${med("wait").toFixed(1)} ms, request ${med("request").toFixed(1)} ms ` +
  `(of which the refit ${med("server").toFixed(1)} ms), from the response to the frame drawn ${med("apply").toFixed(1)} ms ` +
  `(waiting for the frame before ${med("slot").toFixed(1)}, tessellation and buffers ${med("js").toFixed(1)}, drawing ${med("draw").toFixed(1)}, ` +
  `to the next animation frame ${med("show").toFixed(1)})`);
const moves = results.reduce((s, r) => s + r.moves, 0);
const loadEnd = loadavg()[0];
console.log(`load average (1 min) ${loadStart.toFixed(2)} at the start, ${loadEnd.toFixed(2)} at the end, ${cpus().length} cores; ` +
  `moves drawn ${drag.length}, superseded by a newer one ${moves - drag.length} (of ${moves}); ` +
  `full searches while the hand rested ${results.reduce((s, r) => s + r.lat.filter((l) => l.phase === "rest").length, 0)} drawn, ` +
  `${results.reduce((s, r) => s + r.dropped, 0)} dropped as the hand moved on; counts after each drag ${results.map((r) => r.counts.join(" x ")).join(", ")}`);
console.log(`points ${M * N} (${compositing}${hold ? ", shape held" : ""}): mouse event -> new frame shown, quick (drag) p50 ${pctl(drag, 0.5).toFixed(1)} ms, ` +
  `p95 ${pctl(drag, 0.95).toFixed(1)} ms (${drag.length} of ${moves} moves shown, the rest overtaken); ` +
  `every mouse event to the first frame showing it or a newer step: p50 ${pctl(every, 0.5).toFixed(1)} ms, ` +
  `p95 ${pctl(every, 0.95).toFixed(1)} ms; final refit after release p50 ${pctl(fin, 0.5).toFixed(1)} ms`);
await browser.close();
await ed.stop();
rmSync(dir, { recursive: true, force: true });
