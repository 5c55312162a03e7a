// Poses (x, y, z, qx, qy, qz, qw per body) to column-major 4×4 instance
// matrices, interpolated between two steps. Written straight into
// `InstancedMesh.instanceMatrix.array`: no object per balloon, no allocation.

import { POSE_STRIDE } from "../sim/poseLayout";

// The pose layout is the engine's (sim/): kept reachable from here for the renderer's modules.
export { POSE_STRIDE, transformPoint } from "../sim/poseLayout";

/**
 * Writes `count` matrices into `out` (16 floats each), blending poses
 * `prev` and `curr` by `alpha` in [0, 1] (position lerp, quaternion nlerp on
 * the short arc), with a uniform `scale` per body from `scales` (or 1).
 */
export function writeInstanceMatrices(
  out: Float32Array,
  prev: Float32Array,
  curr: Float32Array,
  count: number,
  alpha: number,
  scales: Float32Array | null = null,
): void {
  const a = Math.min(1, Math.max(0, alpha));
  const b = 1 - a;
  for (let i = 0; i < count; i++) {
    const p = i * POSE_STRIDE;
    const x = prev[p] * b + curr[p] * a;
    const y = prev[p + 1] * b + curr[p + 1] * a;
    const z = prev[p + 2] * b + curr[p + 2] * a;
    // Short arc: q and −q are the same rotation.
    const sign = prev[p + 3] * curr[p + 3] + prev[p + 4] * curr[p + 4] + prev[p + 5] * curr[p + 5] + prev[p + 6] * curr[p + 6] < 0 ? -1 : 1;
    let qx = prev[p + 3] * b + sign * curr[p + 3] * a;
    let qy = prev[p + 4] * b + sign * curr[p + 4] * a;
    let qz = prev[p + 5] * b + sign * curr[p + 5] * a;
    let qw = prev[p + 6] * b + sign * curr[p + 6] * a;
    const len = Math.hypot(qx, qy, qz, qw);
    if (len > 0) {
      qx /= len;
      qy /= len;
      qz /= len;
      qw /= len;
    } else {
      qw = 1;
    }
    const s = scales ? scales[i] : 1;
    composeMatrix(out, i * 16, x, y, z, qx, qy, qz, qw, s);
  }
}

/** Column-major TRS matrix (as three's Matrix4.compose) at `out[o..o+16]`. */
export function composeMatrix(
  out: Float32Array,
  o: number,
  x: number,
  y: number,
  z: number,
  qx: number,
  qy: number,
  qz: number,
  qw: number,
  s: number,
): void {
  const x2 = qx + qx;
  const y2 = qy + qy;
  const z2 = qz + qz;
  const xx = qx * x2;
  const xy = qx * y2;
  const xz = qx * z2;
  const yy = qy * y2;
  const yz = qy * z2;
  const zz = qz * z2;
  const wx = qw * x2;
  const wy = qw * y2;
  const wz = qw * z2;
  out[o] = (1 - (yy + zz)) * s;
  out[o + 1] = (xy + wz) * s;
  out[o + 2] = (xz - wy) * s;
  out[o + 3] = 0;
  out[o + 4] = (xy - wz) * s;
  out[o + 5] = (1 - (xx + zz)) * s;
  out[o + 6] = (yz + wx) * s;
  out[o + 7] = 0;
  out[o + 8] = (xz + wy) * s;
  out[o + 9] = (yz - wx) * s;
  out[o + 10] = (1 - (xx + yy)) * s;
  out[o + 11] = 0;
  out[o + 12] = x;
  out[o + 13] = y;
  out[o + 14] = z;
  out[o + 15] = 1;
}
