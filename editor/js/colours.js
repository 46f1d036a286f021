// Colour maps: deviation as a fraction of T (0 blue, 0.5 green, 1 red, beyond: magenta),
// curvature diverging around 0.
export function deviationColour(r, out, o) {
  let c;
  if (!(r >= 0)) c = [0.5, 0.5, 0.5];
  else if (r > 1) c = [1, 0, 1];
  else if (r < 0.5) { const t = r / 0.5; c = [0.1, 0.3 + 0.6 * t, 1 - 0.8 * t]; }
  else { const t = (r - 0.5) / 0.5; c = [0.1 + 0.9 * t, 0.9 - 0.7 * t, 0.2 - 0.1 * t]; }
  out[o] = c[0]; out[o + 1] = c[1]; out[o + 2] = c[2];
}

export function curvatureColour(x, out, o) {  // x in [-1, 1]
  const t = Math.max(-1, Math.min(1, x));
  if (t < 0) { out[o] = 1 + t * 0.8; out[o + 1] = 1 + t * 0.6; out[o + 2] = 1; }
  else { out[o] = 1; out[o + 1] = 1 - t * 0.6; out[o + 2] = 1 - t * 0.8; }
}
