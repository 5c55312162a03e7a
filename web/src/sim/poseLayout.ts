// One body's pose as the engine lays it out in a frame (frameLayout.ts):
// x, y, z (m), then the rotation's quaternion qx, qy, qz, qw; and the world
// point a pose puts a body-frame point at. Pure maths over the pose array,
// read by picking here and by the renderer (render/poseMath.ts).

/** Floats per pose; `checkLayout` holds it to the module's `constants().pose_stride`. */
export const POSE_STRIDE = 7;

/** Rotates body-frame point (lx, ly, lz) by the pose's quaternion and adds its position: the world point, into `out`. */
export function transformPoint(pose: Float32Array, o: number, lx: number, ly: number, lz: number, out: number[]): void {
  const qx = pose[o + 3];
  const qy = pose[o + 4];
  const qz = pose[o + 5];
  const qw = pose[o + 6];
  // v' = v + 2w(q×v) + 2q×(q×v)
  const tx = 2 * (qy * lz - qz * ly);
  const ty = 2 * (qz * lx - qx * lz);
  const tz = 2 * (qx * ly - qy * lx);
  out[0] = lx + qw * tx + (qy * tz - qz * ty) + pose[o];
  out[1] = ly + qw * ty + (qz * tx - qx * tz) + pose[o + 1];
  out[2] = lz + qw * tz + (qx * ty - qy * tx) + pose[o + 2];
}
