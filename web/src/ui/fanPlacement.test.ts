import { describe, expect, it } from "vitest";
import { FAN_DIAMETER_M, FAN_OUTLET_HEIGHT_M, FAN_PICK_RADIUS_M, FAN_SWEEP_DEG, MIN_AIM_DRAG_M, defaultFanAim, fanAimFromDrag, fanAt, fanNear } from "./fanPlacement";
import type { AirSource } from "../sim/airLayout";

describe("the fan tool", () => {
  it("aims a fan level, from where the press went down toward where the drag ended", () => {
    const aim = fanAimFromDrag([1, 1], [4, 5])!;
    expect(aim[0]).toBeCloseTo(0.6, 9);
    expect(aim[1]).toBe(0);
    expect(aim[2]).toBeCloseTo(0.8, 9);
    expect(fanAimFromDrag([1, 1], [1 + MIN_AIM_DRAG_M / 2, 1])).toBeNull();
  });

  it("faces a clicked fan to the room's centre", () => {
    const aim = defaultFanAim([2, 0], [0, 0]);
    expect(aim).toEqual([-1, 0, 0]);
    expect(defaultFanAim([0, 0], [0, 0])).toEqual([0, 0, 1]);
  });

  it("asks the engine for a pedestal fan over the clicked point", () => {
    const fan = fanAt([1, -2], 0, [0, 0, 1], 4, true);
    expect(fan.position).toEqual([1, FAN_OUTLET_HEIGHT_M, -2]);
    expect(fan.direction).toEqual([0, 0, 1]);
    expect(fan.diameter_m).toBe(FAN_DIAMETER_M);
    expect(fan.speed_m_s).toBe(4);
    expect(fan.sweep_deg).toBe(FAN_SWEEP_DEG);
    expect(fanAt([1, -2], 0, [0, 0, 1], 4, false).sweep_deg).toBe(0);
  });

  it("picks the nearest fan's stand instead of placing when a click lands on one", () => {
    const source = (jet: number, x: number, kind: AirSource["kind"] = "fan"): AirSource => ({
      kind,
      jet,
      outlet: [x, 1, 0],
      aim: [0, 0, 1],
      speed: 3,
      fullSpeed: 3,
      diameter: 0.4,
      sweep: 0,
    });
    const sources = [source(0, 0), source(1, 0.5), source(2, 0.2, "vent")];
    expect(fanNear([0.3, 0], sources)).toBe(1);
    expect(fanNear([0.1, 0], sources)).toBe(0);
    expect(fanNear([0, FAN_PICK_RADIUS_M + 0.01], sources)).toBe(-1);
  });
});
