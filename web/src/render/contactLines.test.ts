import { describe, expect, it } from "vitest";
import { BALLOON_CONTACT_COLOR, RIBBON_CONTACT_COLOR, ROOM_CONTACT_COLOR, contactArrays, writeContactGeometry } from "./contactLines";

// Three contacts: one between balloons (normal +x), one with the ceiling (normal +y, into it), one of two ribbons.
const src = new Float32Array([
  1, 2, 3, 1, 0, 0, -0.002, 1,
  0, 4.5, 0, 0, 1, 0, 0.001, 0,
  0.5, 1, 0.5, 0, 1, 0, 0, 2,
]);

describe("contact points to debug geometry", () => {
  it("writes a point and a segment against the normal per contact", () => {
    const out = contactArrays(4);
    expect(writeContactGeometry(src, 2, out, 0.1)).toBe(2);
    expect(Array.from(out.points.slice(0, 6))).toEqual([1, 2, 3, 0, 4.5, 0]);
    const lines = Array.from(out.lines.slice(0, 12));
    [1, 2, 3, 0.9, 2, 3, 0, 4.5, 0, 0, 4.4, 0].forEach((v, i) => expect(lines[i]).toBeCloseTo(v, 6));
  });

  it("colours balloon, room and ribbon contacts apart", () => {
    const out = contactArrays(3);
    writeContactGeometry(src, 3, out, 0.1);
    expect(Array.from(out.pointColors.slice(0, 3))).toEqual(BALLOON_CONTACT_COLOR.map(Math.fround));
    expect(Array.from(out.lineColors.slice(6, 12))).toEqual([...ROOM_CONTACT_COLOR, ...ROOM_CONTACT_COLOR].map(Math.fround));
    expect(Array.from(out.pointColors.slice(6, 9))).toEqual(RIBBON_CONTACT_COLOR.map(Math.fround));
  });

  it("writes no more than fits or than the source holds", () => {
    expect(writeContactGeometry(src, 2, contactArrays(1), 0.1)).toBe(1);
    expect(writeContactGeometry(src, 5, contactArrays(8), 0.1)).toBe(3);
    expect(writeContactGeometry(src, 0, contactArrays(8), 0.1)).toBe(0);
  });
});
