import { describe, expect, it } from "vitest";
import { CONTACT_STRIDE, RIBBON_POINT_STRIDE, SQUASH_STRIDE, frameFloats, frameViews } from "./frameLayout";

describe("frame buffer layout", () => {
  it("lays out previous poses, current poses and contacts without overlap", () => {
    const count = 2;
    const prev = Float32Array.from({ length: 14 }, (_, i) => i);
    const curr = Float32Array.from({ length: 14 }, (_, i) => 100 + i);
    const contacts = Float32Array.from({ length: 3 * CONTACT_STRIDE }, (_, i) => 1000 + i);
    expect(frameFloats(count, 3)).toBe(28 + 24 + 2 + 8);
    const buffer = new ArrayBuffer(frameFloats(count, 3) * 4 + 64); // a reused buffer may be larger
    const w = frameViews(buffer, count, 3);
    w.contacts.set(contacts); // the worker copies contacts first, then the poses
    w.curr.set(curr);
    w.prev.set(prev);
    const v = frameViews(buffer, count, 3);
    expect(v.contacts.byteOffset).toBe(28 * 4);
    expect(Array.from(v.prev)).toEqual(Array.from(prev));
    expect(Array.from(v.curr)).toEqual(Array.from(curr));
    expect(Array.from(v.contacts)).toEqual(Array.from(contacts));
  });

  it("has an empty contacts view when the debug view is off", () => {
    const buffer = new ArrayBuffer(frameFloats(1, 0) * 4);
    frameViews(buffer, 1, 0).curr.fill(2);
    const v = frameViews(buffer, 1, 0);
    expect(v.contacts.length).toBe(0);
    expect(v.curr[6]).toBe(2);
  });

  it("puts the ribbons' previous and current points after the contacts", () => {
    const ribbonFloats = 2 * RIBBON_POINT_STRIDE;
    expect(frameFloats(1, 2, ribbonFloats)).toBe(14 + 16 + 12 + 1 + 4);
    const buffer = new ArrayBuffer(frameFloats(1, 2, ribbonFloats) * 4);
    const w = frameViews(buffer, 1, 2, ribbonFloats);
    w.ribbonsCurr.fill(9);
    w.ribbonsPrev.fill(8);
    w.contacts.fill(7);
    w.curr.fill(6);
    const v = frameViews(buffer, 1, 2, ribbonFloats);
    expect(v.ribbonsPrev.byteOffset).toBe((14 + 16) * 4);
    expect(Array.from(v.ribbonsPrev)).toEqual(Array(6).fill(8));
    expect(Array.from(v.ribbonsCurr)).toEqual(Array(6).fill(9));
    expect(v.contacts[15]).toBe(7);
    expect(() => frameViews(buffer, 1, 2, ribbonFloats + 3)).toThrow(/ribbon points/);
  });

  it("puts one scale per body after the ribbons", () => {
    const ribbonFloats = 3 * RIBBON_POINT_STRIDE;
    const buffer = new ArrayBuffer(frameFloats(2, 1, ribbonFloats) * 4);
    const w = frameViews(buffer, 2, 1, ribbonFloats);
    w.scales.set([0.9, 0.8]);
    w.ribbonsCurr.fill(5);
    w.curr.fill(4);
    const v = frameViews(buffer, 2, 1, ribbonFloats);
    expect(v.scales.length).toBe(2);
    expect(v.scales.byteOffset).toBe((28 + 8 + 18) * 4);
    expect(Array.from(v.scales)).toEqual([Math.fround(0.9), Math.fround(0.8)]);
    expect(v.ribbonsCurr[8]).toBe(5);
  });

  it("ends with each body's squash, after the scales", () => {
    const buffer = new ArrayBuffer(frameFloats(2, 1, 3) * 4);
    const w = frameViews(buffer, 2, 1, 3);
    w.squash.set([0, 0.02, 0, 0.14, 0, 0, 0, 0]);
    w.scales.set([0.5, 0.25]);
    const v = frameViews(buffer, 2, 1, 3);
    expect(SQUASH_STRIDE).toBe(4);
    expect(v.squash.length).toBe(2 * SQUASH_STRIDE);
    expect(v.squash.byteOffset).toBe(v.scales.byteOffset + v.scales.byteLength);
    expect(v.squash.byteOffset + v.squash.byteLength).toBe(buffer.byteLength);
    expect(Array.from(v.squash)).toEqual([0, Math.fround(0.02), 0, Math.fround(0.14), 0, 0, 0, 0]);
    expect(Array.from(v.scales)).toEqual([0.5, 0.25]);
  });

  it("refuses a buffer too small for what the frame claims", () => {
    expect(() => frameViews(new ArrayBuffer(4 * 14), 1, 1)).toThrow(RangeError);
  });
});
