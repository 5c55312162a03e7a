import { describe, expect, it } from "vitest";
import { brightness, meanAbsDifference } from "./pixels";

describe("meanAbsDifference", () => {
  it("is 0 for the same picture and the mean channel difference otherwise, alpha left out", () => {
    const a = new Uint8Array([10, 20, 30, 255, 0, 0, 0, 255]);
    expect(meanAbsDifference(a, a.slice())).toBe(0);
    const b = new Uint8Array([16, 20, 24, 0, 3, 3, 3, 0]);
    // (6 + 0 + 6 + 3 + 3 + 3) / 6 channels
    expect(meanAbsDifference(a, b)).toBeCloseTo(21 / 6, 12);
    expect(meanAbsDifference(b, a)).toBeCloseTo(21 / 6, 12);
  });

  it("is 255 between black and white", () => {
    const black = new Uint8Array(40).fill(0);
    const white = new Uint8Array(40).fill(255);
    expect(meanAbsDifference(black, white)).toBe(255);
  });

  it("refuses pictures of different sizes", () => {
    expect(() => meanAbsDifference(new Uint8Array(8), new Uint8Array(4))).toThrow(/different sizes/);
  });
});

describe("brightness", () => {
  it("weights the channels as Rec. 709 and counts pure black pixels", () => {
    const px = new Uint8Array([255, 0, 0, 255, 0, 0, 0, 255]);
    const b = brightness(px);
    expect(b.mean).toBeCloseTo(0.2126 * 255 / 2, 9);
    expect(b.black).toBe(0.5);
  });
});
