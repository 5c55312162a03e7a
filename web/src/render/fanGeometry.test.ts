import { describe, expect, it } from "vitest";
import { MAX_DRAWN_REV_S, MOTOR_BEHIND_D, bladeTurnRate, fanPose, quaternionFromZ, rotate } from "./fanGeometry";
import type { Vec3 } from "../sim/airLayout";

const close = (a: readonly number[], b: readonly number[]) => a.forEach((v, i) => expect(v).toBeCloseTo(b[i], 6));

describe("a drawn fan", () => {
  it("turns its head from +z onto where it blows, for any aim", () => {
    const aims: Vec3[] = [[0, 0, 1], [1, 0, 0], [0, 1, 0], [0, 0, -1], [0.6, 0.0, -0.8], [0.48, 0.6, 0.64]];
    for (const aim of aims) {
      const q = quaternionFromZ(aim);
      expect(Math.hypot(...q)).toBeCloseTo(1, 9);
      close(rotate(q, [0, 0, 1]), aim);
    }
  });

  it("stands on a pole from the floor to its motor, behind the outlet", () => {
    const pose = fanPose([1, 1.2, -2], [0, 0, 1], 0.4, 0);
    close(pose.head.motor, [1, 1.2, -2 - MOTOR_BEHIND_D * 0.4]);
    close(pose.pole.bottom, [1, 0, -2 - MOTOR_BEHIND_D * 0.4]);
    expect(pose.pole.length).toBeCloseTo(1.2, 6);
    close(pose.base, pose.pole.bottom);
    // A fan on the floor blowing up has no pole.
    expect(fanPose([0, 0.1, 0], [0, 1, 0], 0.4, 0).pole.length).toBe(0);
  });

  it("turns its blades faster the faster it blows, up to a rate a picture can show", () => {
    expect(bladeTurnRate(0, 0.4)).toBe(0);
    expect(bladeTurnRate(1, 0.4)).toBeCloseTo((2 * Math.PI * 1) / (Math.PI * 0.4), 9);
    expect(bladeTurnRate(2, 0.4)).toBeGreaterThan(bladeTurnRate(1, 0.4));
    expect(bladeTurnRate(30, 0.4)).toBeCloseTo(2 * Math.PI * MAX_DRAWN_REV_S, 9);
    expect(bladeTurnRate(Number.NaN, 0.4)).toBe(0);
  });
});
