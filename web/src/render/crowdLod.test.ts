import { describe, expect, it } from "vitest";
import { revolutionProfile, thinProfile } from "./crowdLod";

/** Positions of a surface of revolution: rings of `segments` vertices at the given (r, y), poles single. */
function lathe(profile: [number, number][], segments: number): number[] {
  const out: number[] = [];
  for (const [r, y] of profile) {
    const k = r === 0 ? 1 : segments;
    for (let s = 0; s < k; s++) {
      const a = (2 * Math.PI * s) / k;
      out.push(r * Math.cos(a), y, r * Math.sin(a));
    }
  }
  return out;
}

describe("crowd level of detail", () => {
  const profile: [number, number][] = [
    [0, -0.27],
    [0.01, -0.26],
    [0.1, -0.1],
    [0.14, 0],
    [0.07, 0.1],
    [0, 0.119],
  ];

  it("recovers the profile of a surface of revolution, bottom to top", () => {
    const found = revolutionProfile(lathe([...profile].reverse(), 36));
    expect(found.length).toBe(profile.length);
    found.forEach(([r, y], i) => {
      expect(r).toBeCloseTo(profile[i][0], 5);
      expect(y).toBeCloseTo(profile[i][1], 5);
    });
  });

  it("thins the rings but keeps both poles", () => {
    const thin = thinProfile(profile, 2);
    expect(thin[0]).toEqual(profile[0]);
    expect(thin[thin.length - 1]).toEqual(profile[profile.length - 1]);
    expect(thin.length).toBe(4);
    expect(thinProfile(profile, 1)).toEqual(profile);
  });
});
