// Contact points to debug-view geometry: one point per contact and one short
// segment along its normal, written into preallocated position and colour
// arrays (three's Points and LineSegments draw them with a drawRange).

import { CONTACT_STRIDE } from "../sim/frameLayout";

/** Linear RGB of a contact between two balloons. */
export const BALLOON_CONTACT_COLOR: readonly [number, number, number] = [1, 0.08, 0.02];
/** Linear RGB of a contact with the room. */
export const ROOM_CONTACT_COLOR: readonly [number, number, number] = [0.1, 0.2, 1];
/** Linear RGB of a ribbon touching a ribbon. */
export const RIBBON_CONTACT_COLOR: readonly [number, number, number] = [1, 0.8, 0];

/** A contact's colour by its kind, as up-wasm writes it (0 the room, 1 a balloon, 2 ribbons). */
function kindColor(kind: number): readonly [number, number, number] {
  if (kind > 1.5) return RIBBON_CONTACT_COLOR;
  return kind > 0.5 ? BALLOON_CONTACT_COLOR : ROOM_CONTACT_COLOR;
}

export interface ContactArrays {
  /** x, y, z per contact point. */
  points: Float32Array;
  /** Two vertices (x, y, z) per contact: the point, and the point moved `normalLength` against the normal. */
  lines: Float32Array;
  /** r, g, b per point (the segments' two vertices use the same colour, in `lineColors`). */
  pointColors: Float32Array;
  lineColors: Float32Array;
}

/** Arrays for at most `capacity` contacts. */
export function contactArrays(capacity: number): ContactArrays {
  return {
    points: new Float32Array(capacity * 3),
    lines: new Float32Array(capacity * 6),
    pointColors: new Float32Array(capacity * 3),
    lineColors: new Float32Array(capacity * 6),
  };
}

/**
 * Writes `count` contacts of `src` (CONTACT_STRIDE floats each) into `out`,
 * as many as fit; returns how many were written. The segment points against
 * the normal, from what the balloon touches into the balloon: the way the
 * contact pushes it, and into the room for a wall or ceiling contact.
 */
export function writeContactGeometry(src: Float32Array, count: number, out: ContactArrays, normalLength: number): number {
  const n = Math.min(count, Math.floor(src.length / CONTACT_STRIDE), Math.floor(out.points.length / 3));
  for (let i = 0; i < n; i++) {
    const s = i * CONTACT_STRIDE;
    const x = src[s];
    const y = src[s + 1];
    const z = src[s + 2];
    const color = kindColor(src[s + 7]);
    const p = i * 3;
    out.points[p] = x;
    out.points[p + 1] = y;
    out.points[p + 2] = z;
    const l = i * 6;
    out.lines[l] = x;
    out.lines[l + 1] = y;
    out.lines[l + 2] = z;
    out.lines[l + 3] = x - src[s + 3] * normalLength;
    out.lines[l + 4] = y - src[s + 4] * normalLength;
    out.lines[l + 5] = z - src[s + 5] * normalLength;
    for (let c = 0; c < 3; c++) {
      out.pointColors[p + c] = color[c];
      out.lineColors[l + c] = color[c];
      out.lineColors[l + 3 + c] = color[c];
    }
  }
  return n;
}
