// Layout of one frame buffer from the worker: the poses before and after the
// last step, then (only while the debug view is on) the step's contacts, then
// the ribbons' points before and after the last step, then each body's size
// over its shape's (its gas's; 1 without gas).
//
//   [ previous poses | current poses | contacts          | previous ribbons | current ribbons | scales ]
//     count × 7        count × 7       contactCount × 8    ribbonFloats       ribbonFloats      count     floats

import { POSE_STRIDE } from "./poseLayout";
import type { ContactStride, PoseStride, RibbonPointStride, SquashStride } from "../../public/wasm/up_wasm";
import type { Constants } from "./engine";

/**
 * Floats per contact, as up-wasm writes them (its `constants().contact_stride`):
 * x, y, z (m), nx, ny, nz (unit, from the balloon toward what it touches),
 * separation (m, negative when overlapping), kind (1 balloon, 0 room, 2 a
 * ribbon touching a ribbon, its normal from one toward the other).
 * The renderer's loops need the stride as a constant: its type is the module's
 * (`ContactStride`), and `checkLayout` holds it to the module's when the engine starts.
 */
export const CONTACT_STRIDE: ContactStride = 8;

/** Floats per ribbon point, x, y, z, as up-wasm writes them (`constants().ribbon_point_stride`). */
export const RIBBON_POINT_STRIDE: RibbonPointStride = 3;

/** Floats per body of the squash table: the dent's normal times its depth (x, y, z, m, world), and the reach (m) from the body's origin to the contact along it. */
export const SQUASH_STRIDE: SquashStride = 4;

/** The strides the page reads with, typed by the module's .d.ts: a page built against other strides does not compile. */
const PAGE_STRIDES: { pose: PoseStride; contact: ContactStride; ribbon: RibbonPointStride } = {
  pose: POSE_STRIDE,
  contact: CONTACT_STRIDE,
  ribbon: RIBBON_POINT_STRIDE,
};

/**
 * Throws unless the strides the page reads frames with are the module's own
 * (`constants()` of up-wasm): a page built against another engine stops at
 * start with a message instead of drawing garbage.
 */
export function checkLayout(constants: Pick<Constants, "pose_stride" | "contact_stride" | "ribbon_point_stride">): void {
  const wrong = [
    ["pose", constants.pose_stride, PAGE_STRIDES.pose],
    ["contact", constants.contact_stride, PAGE_STRIDES.contact],
    ["ribbon point", constants.ribbon_point_stride, PAGE_STRIDES.ribbon],
  ].filter(([, engine, page]) => engine !== page);
  if (wrong.length > 0) {
    const say = wrong.map(([what, engine, page]) => `${engine} floats per ${what}, the page reads ${page}`).join("; ");
    throw new Error(`the physics engine does not match the page: the engine writes ${say}; rebuild both`);
  }
}

export interface FrameViews {
  prev: Float32Array<ArrayBuffer>;
  curr: Float32Array<ArrayBuffer>;
  contacts: Float32Array<ArrayBuffer>;
  /** Every ribbon's points before and after the last step, `RIBBON_POINT_STRIDE` each. */
  ribbonsPrev: Float32Array<ArrayBuffer>;
  ribbonsCurr: Float32Array<ArrayBuffer>;
  /** Each body's size now over its shape's, one per body (a balloon shrinks as its gas leaves). */
  scales: Float32Array<ArrayBuffer>;
  /** Each body's deepest dent since the previous frame, `SQUASH_STRIDE` each (zeros: none). */
  squash: Float32Array<ArrayBuffer>;
}

/** Floats a frame of `count` bodies, `contactCount` contacts and `ribbonFloats` floats of ribbon points needs. */
export function frameFloats(count: number, contactCount: number, ribbonFloats = 0): number {
  return 2 * count * POSE_STRIDE + contactCount * CONTACT_STRIDE + 2 * ribbonFloats + count * (1 + SQUASH_STRIDE);
}

/** Views of the parts of a frame buffer (no copy). */
export function frameViews(buffer: ArrayBuffer, count: number, contactCount: number, ribbonFloats = 0): FrameViews {
  const poses = count * POSE_STRIDE;
  const floats = frameFloats(count, contactCount, ribbonFloats);
  if (buffer.byteLength < floats * 4) {
    throw new RangeError(
      `a frame of ${count} bodies, ${contactCount} contacts and ${ribbonFloats / RIBBON_POINT_STRIDE} ribbon points needs ${floats * 4} bytes; the buffer has ${buffer.byteLength}`,
    );
  }
  const ribbons = 2 * poses + contactCount * CONTACT_STRIDE;
  return {
    prev: new Float32Array(buffer, 0, poses),
    curr: new Float32Array(buffer, poses * 4, poses),
    contacts: new Float32Array(buffer, poses * 8, contactCount * CONTACT_STRIDE),
    ribbonsPrev: new Float32Array(buffer, ribbons * 4, ribbonFloats),
    ribbonsCurr: new Float32Array(buffer, (ribbons + ribbonFloats) * 4, ribbonFloats),
    scales: new Float32Array(buffer, (ribbons + 2 * ribbonFloats) * 4, count),
    squash: new Float32Array(buffer, (ribbons + 2 * ribbonFloats + count) * 4, count * SQUASH_STRIDE),
  };
}
