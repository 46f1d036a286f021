// The page's tessellation (editor/js/bspline.js) against the direct evaluation S(u, v) at
// every sample, on surfaces fitted by sfit: positions, unit normals orthogonal to the
// derivatives, the kept basis values reused for a second surface on the same knots, and
// buffers reused while the grid keeps its size.
import { test } from "node:test";
import assert from "node:assert/strict";
import { execFileSync } from "node:child_process";
import { mkdtempSync, readFileSync, rmSync } from "node:fs";
import { tmpdir } from "node:os";
import { join } from "node:path";
import { Tessellator, tessellate, evaluate } from "../js/bspline.js";

const SFIT = process.env.SFIT_CLI;
const EXAMPLES = process.env.SFIT_EXAMPLES;
if (!SFIT || !EXAMPLES) throw new Error("set SFIT_CLI and SFIT_EXAMPLES (CTest does)");

function fitted(name, extra = []) {
  const dir = mkdtempSync(join(tmpdir(), "sfit-bspline-test-"));
  try {
    const out = join(dir, "s.json");
    execFileSync(SFIT, ["fit", join(EXAMPLES, name), "-o", out, "-q", ...extra]);
    return JSON.parse(readFileSync(out, "utf8"));
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
}

const diag = (s) => {
  const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
  for (const r of s.control_points) for (const p of r) for (let a = 0; a < 3; a++) {
    lo[a] = Math.min(lo[a], p[a]); hi[a] = Math.max(hi[a], p[a]);
  }
  return Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
};

function check(surface, t, su, sv, centre) {
  const d = diag(surface);
  for (let i = 0; i < su; i++)
    for (let j = 0; j < sv; j++) {
      const k = i * sv + j, u = t.uv[2 * k], v = t.uv[2 * k + 1];
      const s = evaluate(surface, u, v);
      for (let a = 0; a < 3; a++)  // float32 positions, less the centre
        assert.ok(Math.abs(t.position[3 * k + a] + centre[a] - s[a]) <= 1e-6 * d, `sample ${i}, ${j} axis ${a}`);
      const n = [0, 1, 2].map((a) => t.normal[3 * k + a]);
      assert.ok(Math.abs(Math.hypot(...n) - 1) < 1e-5, `unit normal at ${i}, ${j}`);
      // The normal is orthogonal to the surface: S at a nearby sample differs along it little.
      const h = 1e-4;
      const su_ = evaluate(surface, Math.min(u + h, surface.knots_u.at(-1)), v);
      const tangent = su_.map((x, a) => x - s[a]);
      const len = Math.hypot(...tangent);
      if (len > 0) assert.ok(Math.abs(tangent.reduce((acc, x, a) => acc + x * n[a], 0)) / len < 1e-2, `normal at ${i}, ${j}`);
    }
  assert.equal(t.uv[0], surface.knots_u[surface.degree[0]]);
  assert.equal(t.uv[2 * (su * sv - 1)], surface.knots_u[surface.control_points.length]);
}

test("samples lie on the surface, normals are unit and normal (open and closed surfaces)", () => {
  for (const [name, extra] of [["ship_px121_stations.rows", []], ["iea3p4mw_blade_ragged9.rows", ["--closed", "u"]]]) {
    const surface = fitted(name, extra);
    const centre = [1.5, -2, 3];
    check(surface, tessellate(surface, 23, 17, centre), 23, 17, centre);
  }
});

test("the kept basis values serve a second surface on the same knots; buffers are reused", () => {
  const a = fitted("ship_px121_stations.rows");
  const b = JSON.parse(JSON.stringify(a));
  for (const row of b.control_points) for (const p of row) p[2] += 0.25 * Math.sin(p[0]);
  const t = new Tessellator();
  const first = t.run(a, 19, 13);
  const position = first.position;
  const second = t.run(b, 19, 13, [0, 0, 0], true);
  assert.equal(second.position, position, "the same array, overwritten");
  check(b, second, 19, 13, [0, 0, 0]);
  assert.deepEqual(Array.from(second.position), Array.from(tessellate(b, 19, 13).position));
  assert.deepEqual(Array.from(second.mean), Array.from(tessellate(b, 19, 13).mean));
  const bigger = t.run(b, 25, 13);
  assert.notEqual(bigger.position, position, "a new grid size gets new arrays");
  check(b, bigger, 25, 13, [0, 0, 0]);
});
