// Layout of one frame buffer from the worker: the poses before and after the
// last step, then (only while the debug view is on) the step's contacts.
//
//   [ previous poses | current poses | contacts ]
//     count × 7        count × 7       contactCount × 8   floats

import { POSE_STRIDE } from "../render/poseMath";

/**
 * Floats per contact, as up-wasm writes them (crates/up-wasm/src/contacts.rs):
 * x, y, z (m), nx, ny, nz (unit, from the balloon toward what it touches),
 * separation (m, negative when overlapping), kind (1 balloon, 0 room).
 */
export const CONTACT_STRIDE = 8;

export interface FrameViews {
  prev: Float32Array<ArrayBuffer>;
  curr: Float32Array<ArrayBuffer>;
  contacts: Float32Array<ArrayBuffer>;
}

/** Floats a frame of `count` bodies and `contactCount` contacts needs. */
export function frameFloats(count: number, contactCount: number): number {
  return 2 * count * POSE_STRIDE + contactCount * CONTACT_STRIDE;
}

/** Views of the three parts of a frame buffer (no copy). */
export function frameViews(buffer: ArrayBuffer, count: number, contactCount: number): FrameViews {
  const poses = count * POSE_STRIDE;
  if (buffer.byteLength < frameFloats(count, contactCount) * 4) {
    throw new RangeError(`a frame of ${count} bodies and ${contactCount} contacts needs ${frameFloats(count, contactCount) * 4} bytes; the buffer has ${buffer.byteLength}`);
  }
  return {
    prev: new Float32Array(buffer, 0, poses),
    curr: new Float32Array(buffer, poses * 4, poses),
    contacts: new Float32Array(buffer, poses * 8, contactCount * CONTACT_STRIDE),
  };
}
