import { describe, expect, it } from "vitest";
import { MAX_TICK_S, STEP_BUDGET_MS, TIME_LAPSE_RATES, TimeLapse, censusInterval } from "./timeLapse";

describe("time-lapse", () => {
  it("offers real time and the panel's three rates", () => {
    expect([...TIME_LAPSE_RATES]).toEqual([1, 60, 600, 3600]);
    const lapse = new TimeLapse();
    expect(lapse.lapsing).toBe(false);
    lapse.setRate(3600);
    expect(lapse.lapsing).toBe(true);
    expect(() => lapse.setRate(0)).toThrow(/at least 1/);
    expect(() => lapse.setRate(NaN)).toThrow(RangeError);
  });

  it("asks for rate × frame time, a long tick counted as MAX_TICK_S", () => {
    const lapse = new TimeLapse();
    lapse.setRate(600);
    expect(lapse.plan(1 / 60).seconds).toBeCloseTo(10, 9);
    expect(lapse.plan(5).seconds).toBeCloseTo(600 * MAX_TICK_S, 9);
    expect(lapse.plan(-1).seconds).toBe(0);
  });

  it("keeps the steps within the budget as the cost of a step is learnt", () => {
    const lapse = new TimeLapse();
    lapse.setRate(3600);
    // Steps of 2 ms each, tick after tick: the plan converges on 12 / 2 = 6 steps.
    for (let i = 0; i < 50; i++) {
      const { maxSteps } = lapse.plan(1 / 60);
      lapse.record({ seconds: maxSteps / 60, steps: maxSteps, jumps: 0 }, maxSteps * 2, 1 / 60);
    }
    expect(lapse.msPerStep).toBeCloseTo(2, 1);
    expect(lapse.plan(1 / 60).maxSteps).toBe(Math.floor(STEP_BUDGET_MS / 2));
    // Cheap steps (a pile asleep): many more allowed, never fewer than one.
    for (let i = 0; i < 50; i++) lapse.record({ seconds: 60, steps: 100, jumps: 0 }, 1, 1 / 60);
    expect(lapse.plan(1 / 60).maxSteps).toBeGreaterThan(100);
    const slow = new TimeLapse();
    slow.record({ seconds: 0, steps: 60, jumps: 0 }, 60 * 500, 1 / 60);
    expect(slow.plan(1 / 60).maxSteps).toBe(1);
  });

  it("reports the rate achieved, not the one asked, when stepping falls behind", () => {
    const lapse = new TimeLapse();
    lapse.setRate(3600);
    expect(lapse.achieved).toBe(0);
    // Every tick asks 60 s but gets 0.4 s (24 steps of 1/60 s): ×24.
    for (let i = 0; i < 300; i++) lapse.record({ seconds: 0.4, steps: 24, jumps: 0 }, 12, 1 / 60);
    expect(lapse.achieved).toBeCloseTo(24, 6);
    // Then everything sleeps and the jumps keep up: the rate climbs to ×3 600.
    for (let i = 0; i < 600; i++) lapse.record({ seconds: 60, steps: 0, jumps: 1 }, 0.1, 1 / 60);
    expect(lapse.achieved).toBeGreaterThan(3500);
    expect(lapse.achieved).toBeLessThanOrEqual(3600 + 1e-6);
    lapse.setRate(60);
    expect(lapse.achieved, "a new rate starts afresh").toBe(0);
  });

  it("looks at the balloons every simulated second to minute", () => {
    expect(censusInterval(1)).toBe(1);
    expect(censusInterval(60)).toBe(30);
    expect(censusInterval(600)).toBe(60);
    expect(censusInterval(3600)).toBe(60);
  });
});
