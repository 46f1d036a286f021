// A surface whose control points came packed (POST /api/edit?pack=1 or ?pack=f32,
// docs/editor-api.md) made back into the contract's nested "control_points": "control_points_f64"
// (base64 of the little-endian doubles, x y z of each point row by row) exactly;
// "control_points_f32" (floats of each point less "control_points_origin") to within 1e-7 of
// the control points' box, for drawing a drag step.
function decode(text) {
  const bin = atob(text);
  const bytes = new Uint8Array(bin.length);
  for (let i = 0; i < bin.length; i++) bytes[i] = bin.charCodeAt(i);
  return bytes.buffer;
}
/// The little-endian doubles of a base64 text.
export const doubles = (text) => new Float64Array(decode(text));
export function unpack(surface) {
  const f32 = surface.control_points_f32 !== undefined;
  const xyz = f32 ? new Float32Array(decode(surface.control_points_f32)) : new Float64Array(decode(surface.control_points_f64));
  const o = f32 ? surface.control_points_origin : [0, 0, 0];
  const [nu, nv] = surface.control_points_shape;
  if (xyz.length !== nu * nv * 3) throw new Error(`packed control points: ${xyz.length} numbers for ${nu} x ${nv} points`);
  const cp = new Array(nu);
  for (let i = 0, k = 0; i < nu; i++) {
    const row = cp[i] = new Array(nv);
    for (let j = 0; j < nv; j++, k += 3) row[j] = [o[0] + xyz[k], o[1] + xyz[k + 1], o[2] + xyz[k + 2]];
  }
  surface.control_points = cp;
  for (const k of ["control_points_f64", "control_points_f32", "control_points_origin", "control_points_shape"]) delete surface[k];
  return surface;
}
