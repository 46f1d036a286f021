// Shared by the browser tests and the browser benchmark: start `sfit edit` on a copy of a
// data set, launch the system Chromium headless through puppeteer-core.
import { spawn } from "node:child_process";
import { existsSync, mkdtempSync, copyFileSync, rmSync } from "node:fs";
import { tmpdir } from "node:os";
import { join, basename } from "node:path";

export const CHROMIUM = process.env.SFIT_CHROMIUM || "/usr/bin/chromium";

/// Exit code CTest reads as "skipped" (SKIP_RETURN_CODE).
export const SKIP = 77;

export function skipUnlessChromium() {
  if (!existsSync(CHROMIUM)) {
    console.log(`SKIP: ${CHROMIUM} is not installed (Debian package chromium); browser tests not run`);
    process.exit(SKIP);
  }
}

export async function loadPuppeteer() {
  try {
    return (await import("puppeteer-core")).default;
  } catch (e) {
    throw new Error("puppeteer-core is missing: run 'npm ci' in editor/ (scripts/install-deps.sh does)");
  }
}

/// Starts `sfit edit` on a copy of `rows` in a fresh folder (`inPlace`: on `rows` itself, e.g.
/// a second editor of the same file); resolves with {url, port, token, dir, input, proc,
/// stop()} once the server prints its address.
export function startEditor(sfit, rows, extra = [], { inPlace = false } = {}) {
  const dir = inPlace ? null : mkdtempSync(join(tmpdir(), "sfit-edit-test-"));
  const input = inPlace ? rows : join(dir, basename(rows));
  if (!inPlace) copyFileSync(rows, input);
  const cleanup = () => { if (dir) rmSync(dir, { recursive: true, force: true }); };
  const proc = spawn(sfit, ["edit", input, "--no-browser", ...extra], { stdio: ["ignore", "ignore", "pipe"] });
  let err = "";
  const exited = new Promise((res) => proc.on("exit", (code, signal) => res({ code, signal })));
  return new Promise((resolve, reject) => {
    const timer = setTimeout(() => reject(new Error("sfit edit did not start: " + err)), 60000);
    exited.then((r) => {
      clearTimeout(timer);
      cleanup();
      reject(new Error(`sfit edit exited ${r.code}: ${err}`));
    });
    proc.stderr.on("data", (d) => {
      err += d;
      const m = err.match(/sfit: editing (.*) at (http:\/\/127\.0\.0\.1:(\d+)\/\?token=([0-9a-f]+))/);
      if (!m) return;
      clearTimeout(timer);
      resolve({
        url: m[2], port: Number(m[3]), token: m[4], dir, input, proc, stderr: () => err,
        async stop() {
          proc.kill("SIGTERM");
          const r = await exited;
          cleanup();
          return r;
        },
      });
    });
  });
}

// WebGL on SwiftShader (software GL); the page composited in software, as Chromium does on a
// machine without a GPU (compositing on SwiftShader as well, the default once it is enabled,
// costs some 40 ms a frame at 1280 x 800 on 2 cores; SFIT_CHROMIUM_GL_COMPOSITING=1 keeps it).
export async function launch(puppeteer) {
  const profile = mkdtempSync(join(tmpdir(), "sfit-chromium-"));
  const compositing = process.env.SFIT_CHROMIUM_GL_COMPOSITING === "1" ? [] : ["--disable-gpu-compositing"];
  const browser = await puppeteer.launch({
    executablePath: CHROMIUM,
    headless: true,
    args: ["--headless=new", "--no-sandbox", "--enable-unsafe-swiftshader", "--use-angle=swiftshader",
      ...compositing, "--disable-background-networking", "--disable-component-update", "--disable-sync",
      "--no-first-run", `--user-data-dir=${profile}`, "--window-size=1280,800"],
    defaultViewport: { width: 1280, height: 800 },
  });
  const close = browser.close.bind(browser);
  browser.close = async () => { await close(); rmSync(profile, { recursive: true, force: true }); };
  return browser;
}

/// Opens the editor at `url` in a new page of `browser`; page errors go to `errors`.
export async function openPage(browser, url, errors) {
  const page = await browser.newPage();
  page.on("pageerror", (e) => errors.push(e.message));
  await page.goto(url);
  await page.waitForFunction(() => (window.sfitEditor && window.sfitEditor.ready) || window.sfitEditorError,
    { timeout: 60000 });
  const failed = await page.evaluate(() => window.sfitEditorError || null);
  if (failed) throw new Error("the page did not start: " + failed);
  return page;
}
