// A surface whose control points came packed (POST /api/edit?pack=1, docs/editor.md): the
// doubles of "control_points_f64" (base64, little-endian, x y z of each point row by row)
// made back into the contract's nested "control_points", exactly.
export function unpack(surface) {
  const bin = atob(surface.control_points_f64);
  const bytes = new Uint8Array(bin.length);
  for (let i = 0; i < bin.length; i++) bytes[i] = bin.charCodeAt(i);
  const xyz = new Float64Array(bytes.buffer);
  const [nu, nv] = surface.control_points_shape;
  if (xyz.length !== nu * nv * 3) throw new Error(`packed control points: ${xyz.length} numbers for ${nu} x ${nv} points`);
  const cp = new Array(nu);
  for (let i = 0, k = 0; i < nu; i++) {
    const row = cp[i] = new Array(nv);
    for (let j = 0; j < nv; j++, k += 3) row[j] = [xyz[k], xyz[k + 1], xyz[k + 2]];
  }
  surface.control_points = cp;
  delete surface.control_points_f64;
  delete surface.control_points_shape;
  return surface;
}
