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

/// Grid of su x sv samples: positions (less `centre`, for float precision), unit normals, mean and Gaussian curvature, and the
/// (u, v) of each sample.
export function tessellate(surface, su, sv, centre = [0, 0, 0]) {
  const [p, q] = surface.degree;
  const cp = surface.control_points;
  const nu = cp.length, nv = cp[0].length;
  const U = samplesOf(surface.knots_u, p, nu, su);
  const V = samplesOf(surface.knots_v, q, nv, sv);
  const count = su * sv;
  const position = new Float32Array(3 * count), normal = new Float32Array(3 * count);
  const mean = new Float32Array(count), gauss = new Float32Array(count);
  const uv = new Float64Array(2 * count);
  const d = new Float64Array(18);  // S, Su, Sv, Suu, Suv, Svv
  for (let i = 0; i < su; i++) {
    const A = U[i];
    for (let j = 0; j < sv; j++) {
      const B = V[j];
      d.fill(0);
      for (let k = 0; k <= p; k++) {
        const row = cp[A.span - p + k];
        const a0 = A.ders[0][k], a1 = A.ders[1][k], a2 = A.ders[2][k];
        for (let l = 0; l <= q; l++) {
          const P = row[B.span - q + l];
          const b0 = B.ders[0][l], b1 = B.ders[1][l], b2 = B.ders[2][l];
          const w = [a0 * b0, a1 * b0, a0 * b1, a2 * b0, a1 * b1, a0 * b2];
          for (let m = 0; m < 6; m++) {
            d[3 * m] += w[m] * P[0]; d[3 * m + 1] += w[m] * P[1]; d[3 * m + 2] += w[m] * P[2];
          }
        }
      }
      const idx = i * sv + j;
      position[3 * idx] = d[0] - centre[0];
      position[3 * idx + 1] = d[1] - centre[1];
      position[3 * idx + 2] = d[2] - centre[2];
      const su_ = [d[3], d[4], d[5]], sv_ = [d[6], d[7], d[8]];
      let n = [su_[1] * sv_[2] - su_[2] * sv_[1], su_[2] * sv_[0] - su_[0] * sv_[2],
        su_[0] * sv_[1] - su_[1] * sv_[0]];
      const len = Math.hypot(n[0], n[1], n[2]);
      if (len > 0) n = n.map((x) => x / len);
      normal[3 * idx] = n[0]; normal[3 * idx + 1] = n[1]; normal[3 * idx + 2] = n[2];
      const dot = (x, o) => x[0] * d[o] + x[1] * d[o + 1] + x[2] * d[o + 2];
      const E = dot(su_, 3), F = dot(su_, 6), G = dot(sv_, 6);
      const L = dot(n, 9), M = dot(n, 12), N = dot(n, 15);
      const det = E * G - F * F;
      mean[idx] = det > 0 && len > 0 ? (E * N - 2 * F * M + G * L) / (2 * det) : 0;
      gauss[idx] = det > 0 && len > 0 ? (L * N - M * M) / det : 0;
      uv[2 * idx] = A.t; uv[2 * idx + 1] = B.t;
    }
  }
  // A degenerate normal (a pole) takes its neighbour's.
  for (let idx = 0; idx < count; idx++) {
    if (normal[3 * idx] || normal[3 * idx + 1] || normal[3 * idx + 2]) continue;
    const o = idx + sv < count ? idx + sv : idx - sv;
    const s = o >= 0 && o < count ? o : idx;
    for (let c = 0; c < 3; c++) normal[3 * idx + c] = normal[3 * s + c];
  }
  return { su, sv, position, normal, mean, gauss, uv };
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
