// Evaluation of the surface in the JSON surface contract (docs/surface-json.md): full knot
// vectors and control arrays, periodic directions with their wrap copies stored.

function findSpan(knots, p, n, t) {
  if (t >= knots[n]) return n - 1;
  if (t <= knots[p]) return p;
  let lo = p, hi = n;
  while (hi - lo > 1) {
    const mid = (lo + hi) >> 1;
    if (t < knots[mid]) hi = mid; else lo = mid;
  }
  return lo;
}

// Basis functions and their derivatives up to order 2 at t (The NURBS Book, A2.3).
function dersBasis(knots, p, span, t) {
  const ndu = Array.from({ length: p + 1 }, () => new Float64Array(p + 1));
  const left = new Float64Array(p + 1), right = new Float64Array(p + 1);
  ndu[0][0] = 1;
  for (let j = 1; j <= p; j++) {
    left[j] = t - knots[span + 1 - j];
    right[j] = knots[span + j] - t;
    let saved = 0;
    for (let r = 0; r < j; r++) {
      ndu[j][r] = right[r + 1] + left[j - r];
      const tmp = ndu[r][j - 1] / ndu[j][r];
      ndu[r][j] = saved + right[r + 1] * tmp;
      saved = left[j - r] * tmp;
    }
    ndu[j][j] = saved;
  }
  const n = Math.min(2, p);
  const ders = [new Float64Array(p + 1), new Float64Array(p + 1), new Float64Array(p + 1)];
  for (let j = 0; j <= p; j++) ders[0][j] = ndu[j][p];
  const a = [new Float64Array(p + 1), new Float64Array(p + 1)];
  for (let r = 0; r <= p; r++) {
    let s1 = 0, s2 = 1;
    a[0].fill(0); a[1].fill(0);
    a[0][0] = 1;
    for (let k = 1; k <= n; k++) {
      let d = 0;
      const rk = r - k, pk = p - k;
      if (r >= k) {
        a[s2][0] = a[s1][0] / ndu[pk + 1][rk];
        d = a[s2][0] * ndu[rk][pk];
      }
      const j1 = rk >= -1 ? 1 : -rk;
      const j2 = r - 1 <= pk ? k - 1 : p - r;
      for (let j = j1; j <= j2; j++) {
        a[s2][j] = (a[s1][j] - a[s1][j - 1]) / ndu[pk + 1][rk + j];
        d += a[s2][j] * ndu[rk + j][pk];
      }
      if (r <= pk) {
        a[s2][k] = -a[s1][k - 1] / ndu[pk + 1][r];
        d += a[s2][k] * ndu[r][pk];
      }
      ders[k][r] = d;
      const t2 = s1; s1 = s2; s2 = t2;
    }
  }
  let r = p;
  for (let k = 1; k <= n; k++) {
    for (let j = 0; j <= p; j++) ders[k][j] *= r;
    r *= p - k;
  }
  return ders;
}

function samplesOf(knots, p, n, count) {
  const a = knots[p], b = knots[n];
  const out = [];
  for (let i = 0; i < count; i++) {
    const t = a + ((b - a) * i) / (count - 1);
    const span = findSpan(knots, p, n, t);
    out.push({ t, span, ders: dersBasis(knots, p, span, t) });
  }
  return out;
}

/// Samples per direction: `perSpan` per knot span, within [8, max].
export function sampleCounts(surface, perSpan, max) {
  const [p, q] = surface.degree;
  const spansU = surface.control_points.length - p, spansV = surface.control_points[0].length - q;
  const c = (s) => Math.max(8, Math.min(max, s * perSpan + 1));
  return [c(spansU), c(spansV)];
}

/// Tessellates surfaces on an su x sv grid of samples, evenly spaced in (u, v). The basis
/// functions and their derivatives at the samples depend only on the degrees, the knots and
/// the sample counts, which a drag at fixed control-point counts does not change: they are
/// computed once and kept, and each surface costs only the contraction with its control
/// points. Output arrays are reused while the grid keeps its size (for buffers updated in
/// place). Positions are less `centre` (float precision), normals unit length; mean curvature
/// only when asked for.
export class Tessellator {
  constructor() {
    this.key = "";
    this.out = null;
  }

  /// { su, sv, position, normal, mean (or null), uv }; the arrays are this tessellator's own and
  /// are overwritten by the next call.
  run(surface, su, sv, centre = [0, 0, 0], curvature = false) {
    const [p, q] = surface.degree;
    const cp = surface.control_points;
    const nu = cp.length, nv = cp[0].length;
    const key = `${p},${q},${su},${sv}|${surface.knots_u.join(",")}|${surface.knots_v.join(",")}`;
    if (key !== this.key) {
      this.key = key;
      this.U = samplesOf(surface.knots_u, p, nu, su);
      this.V = samplesOf(surface.knots_v, q, nv, sv);
      this.rows = new Float64Array(9 * nv);  // one u sample: S, Su, Suu along each column
    }
    const count = su * sv;
    if (!this.out || this.out.su !== su || this.out.sv !== sv) {
      const uv = new Float64Array(2 * count);
      for (let i = 0; i < su; i++)
        for (let j = 0; j < sv; j++) { uv[2 * (i * sv + j)] = this.U[i].t; uv[2 * (i * sv + j) + 1] = this.V[j].t; }
      this.out = { su, sv, position: new Float32Array(3 * count), normal: new Float32Array(3 * count), mean: null, uv };
    }
    const out = this.out;
    if (curvature && !out.mean) out.mean = new Float32Array(count);
    const { position, normal } = out;
    const mean = curvature ? out.mean : null;
    const R = this.rows;
    const d = new Float64Array(18);  // S, Su, Sv, Suu, Suv, Svv
    for (let i = 0; i < su; i++) {
      const A = this.U[i], a0 = A.ders[0], a1 = A.ders[1], a2 = A.ders[2];
      // Contract along u first: for each column l, the curve's point and u-derivatives.
      R.fill(0);
      for (let k = 0; k <= p; k++) {
        const row = cp[A.span - p + k], w0 = a0[k], w1 = a1[k], w2 = a2[k];
        for (let l = 0; l < nv; l++) {
          const P = row[l], o = 9 * l;
          R[o] += w0 * P[0]; R[o + 1] += w0 * P[1]; R[o + 2] += w0 * P[2];
          R[o + 3] += w1 * P[0]; R[o + 4] += w1 * P[1]; R[o + 5] += w1 * P[2];
          if (curvature) { R[o + 6] += w2 * P[0]; R[o + 7] += w2 * P[1]; R[o + 8] += w2 * P[2]; }
        }
      }
      for (let j = 0; j < sv; j++) {
        const B = this.V[j], b0 = B.ders[0], b1 = B.ders[1], b2 = B.ders[2];
        d.fill(0);
        for (let l = 0; l <= q; l++) {
          const o = 9 * (B.span - q + l), w0 = b0[l], w1 = b1[l], w2 = b2[l];
          for (let c = 0; c < 3; c++) {
            const r0 = R[o + c], r1 = R[o + 3 + c];
            d[c] += w0 * r0;       // S
            d[3 + c] += w0 * r1;   // Su
            d[6 + c] += w1 * r0;   // Sv
            if (curvature) {
              d[9 + c] += w0 * R[o + 6 + c];  // Suu
              d[12 + c] += w1 * r1;           // Suv
              d[15 + c] += w2 * r0;           // Svv
            }
          }
        }
        const idx = i * sv + j, o3 = 3 * idx;
        position[o3] = d[0] - centre[0];
        position[o3 + 1] = d[1] - centre[1];
        position[o3 + 2] = d[2] - centre[2];
        let nx = d[4] * d[8] - d[5] * d[7], ny = d[5] * d[6] - d[3] * d[8], nz = d[3] * d[7] - d[4] * d[6];
        const len = Math.hypot(nx, ny, nz);
        if (len > 0) { nx /= len; ny /= len; nz /= len; }
        normal[o3] = nx; normal[o3 + 1] = ny; normal[o3 + 2] = nz;
        if (curvature) {
          const E = d[3] * d[3] + d[4] * d[4] + d[5] * d[5];
          const F = d[3] * d[6] + d[4] * d[7] + d[5] * d[8];
          const G = d[6] * d[6] + d[7] * d[7] + d[8] * d[8];
          const L = nx * d[9] + ny * d[10] + nz * d[11];
          const M = nx * d[12] + ny * d[13] + nz * d[14];
          const N = nx * d[15] + ny * d[16] + nz * d[17];
          const det = E * G - F * F;
          mean[idx] = det > 0 && len > 0 ? (E * N - 2 * F * M + G * L) / (2 * det) : 0;
        }
      }
    }
    // A degenerate normal (a pole) takes its neighbour's.
    for (let idx = 0; idx < count; idx++) {
      if (normal[3 * idx] || normal[3 * idx + 1] || normal[3 * idx + 2]) continue;
      const o = idx + sv < count ? idx + sv : idx - sv;
      const s = o >= 0 && o < count ? o : idx;
      for (let c = 0; c < 3; c++) normal[3 * idx + c] = normal[3 * s + c];
    }
    return out;
  }
}

/// Grid of su x sv samples, in fresh arrays (Tessellator, with mean curvature).
export function tessellate(surface, su, sv, centre = [0, 0, 0]) {
  return new Tessellator().run(surface, su, sv, centre, true);
}

/// S(u, v) at one parameter pair.
export function evaluate(surface, u, v) {
  const [p, q] = surface.degree;
  const cp = surface.control_points;
  const nu = cp.length, nv = cp[0].length;
  const su = findSpan(surface.knots_u, p, nu, u), sv = findSpan(surface.knots_v, q, nv, v);
  const bu = dersBasis(surface.knots_u, p, su, u)[0], bv = dersBasis(surface.knots_v, q, sv, v)[0];
  const s = [0, 0, 0];
  for (let k = 0; k <= p; k++)
    for (let l = 0; l <= q; l++) {
      const P = cp[su - p + k][sv - q + l], w = bu[k] * bv[l];
      s[0] += w * P[0]; s[1] += w * P[1]; s[2] += w * P[2];
    }
  return s;
}
