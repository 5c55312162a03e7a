import { describe, expect, it } from "vitest";
import {
  ELEVATION_LIMIT,
  clampElevation,
  orbitAngles,
  orbitPosition,
  portraitPullBack,
  stepOrbit,
  wrapAngle,
} from "./orbit";

const center = { x: 0, y: 1.5, z: 0 };
const none = { left: false, right: false, up: false, down: false };

describe("orbit maths", () => {
  it("puts azimuth 0, elevation 0 on the +Z axis", () => {
    const p = orbitPosition(center, { azimuth: 0, elevation: 0, distance: 10 });
    expect(p.x).toBeCloseTo(0, 6);
    expect(p.y).toBeCloseTo(1.5, 6);
    expect(p.z).toBeCloseTo(10, 6);
  });

  it("round-trips between angles and position", () => {
    const angles = { azimuth: 0.7, elevation: -0.4, distance: 6.5 };
    const back = orbitAngles(center, orbitPosition(center, angles));
    expect(back.azimuth).toBeCloseTo(angles.azimuth, 6);
    expect(back.elevation).toBeCloseTo(angles.elevation, 6);
    expect(back.distance).toBeCloseTo(angles.distance, 6);
  });

  it("keeps the distance constant while the keys are held", () => {
    let angles = { azimuth: 0.2, elevation: 0.3, distance: 8 };
    const keys = { left: true, right: false, up: true, down: false };
    for (let i = 0; i < 500; i++) {
      angles = stepOrbit(angles, keys, 1 / 60);
      const p = orbitPosition(center, angles);
      expect(Math.hypot(p.x - center.x, p.y - center.y, p.z - center.z)).toBeCloseTo(8, 5);
    }
  });

  it("turns left and right in opposite directions and at the given rate", () => {
    const start = { azimuth: 0, elevation: 0, distance: 5 };
    const right = stepOrbit(start, { ...none, right: true }, 0.5, 1);
    const left = stepOrbit(start, { ...none, left: true }, 0.5, 1);
    expect(right.azimuth).toBeCloseTo(0.5, 9);
    expect(left.azimuth).toBeCloseTo(-0.5, 9);
    expect(stepOrbit(start, none, 0.5, 1)).toEqual(start);
  });

  it("clamps the elevation short of the poles", () => {
    let angles = { azimuth: 0, elevation: 0, distance: 5 };
    for (let i = 0; i < 1000; i++) angles = stepOrbit(angles, { ...none, up: true }, 1 / 30);
    expect(angles.elevation).toBe(ELEVATION_LIMIT);
    for (let i = 0; i < 1000; i++) angles = stepOrbit(angles, { ...none, down: true }, 1 / 30);
    expect(angles.elevation).toBe(-ELEVATION_LIMIT);
    expect(clampElevation(0.1)).toBe(0.1);
  });

  it("wraps the azimuth into (-pi, pi]", () => {
    expect(wrapAngle(Math.PI + 0.1)).toBeCloseTo(-Math.PI + 0.1, 9);
    expect(wrapAngle(-Math.PI - 0.1)).toBeCloseTo(Math.PI - 0.1, 9);
    expect(wrapAngle(7 * Math.PI)).toBeCloseTo(Math.PI, 9);
  });

  it("handles a camera sitting on the centre", () => {
    expect(orbitAngles(center, center)).toEqual({ azimuth: 0, elevation: 0, distance: 0 });
  });
});

describe("the home view in a portrait window", () => {
  it("stands where it stands in a landscape window, and farther back as the window narrows", () => {
    expect(portraitPullBack(1.6)).toBe(1);
    expect(portraitPullBack(1)).toBe(1);
    const phone = portraitPullBack(390 / 844);
    expect(phone).toBeGreaterThan(1.5);
    expect(phone).toBeLessThan(2);
    expect(portraitPullBack(0.75)).toBeLessThan(phone);
    // A sliver of a window does not send the camera out of sight.
    expect(portraitPullBack(0.01)).toBe(portraitPullBack(0.3));
  });
});
