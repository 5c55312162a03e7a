import { describe, expect, it } from "vitest";
import { MAX_AIR_ARROW_M, METRES_PER_M_S, airArrow } from "./airArrow";

describe("the air's arrow", () => {
  it("points where the air goes, its length the air's speed to scale, cut at its longest", () => {
    const a = airArrow([0, 0, 2])!;
    expect(a.direction).toEqual([0, 0, 1]);
    expect(a.length).toBeCloseTo(2 * METRES_PER_M_S, 9);
    expect(airArrow([30, 0, 0])!.length).toBe(MAX_AIR_ARROW_M);
    expect(airArrow([0.001, 0, 0])).toBeNull();
    expect(airArrow([Number.NaN, 0, 0])).toBeNull();
  });
});
