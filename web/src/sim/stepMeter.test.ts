import { beforeAll, describe, expect, it } from "vitest";
import { loadBuiltEngine } from "./builtEngine";
import type { Engine } from "./engine";
import { MAX_MEASURED_STEPS, hashHex, measureSteps } from "./stepMeter";

const SCENE = JSON.stringify({ room: { width: 4, depth: 4 }, balloons: [{ count: 40 }], sim: { seed: 3 } });

let engine: Engine;

beforeAll(async () => {
  engine = await loadBuiltEngine();
});

describe("measureSteps", () => {
  it("times every step of the window with the engine's timer and the worker's clock", () => {
    engine.loadSceneJson(SCENE);
    const r = measureSteps(engine, 12);
    expect(r.steps).toBe(12);
    expect(r.engineMs).toHaveLength(12);
    expect(r.wallMs).toHaveLength(12);
    // The engine's time is inside the call's.
    for (let i = 0; i < 12; i++) {
      expect(r.engineMs[i]).toBeGreaterThan(0);
      expect(r.wallMs[i]).toBeGreaterThanOrEqual(r.engineMs[i] * 0.5);
    }
    expect(r.bodies).toBe(40);
    // The stages' means: the engine's names, "total" last, which is the mean of the steps' totals.
    const names = r.stageMeanMs.map(([name]) => name);
    expect(names).toContain("solve");
    expect(names.at(-1)).toBe("total");
    const meanTotal = r.engineMs.reduce((a, b) => a + b, 0) / r.engineMs.length;
    expect(r.stageMeanMs.at(-1)![1]).toBeCloseTo(meanTotal, 9);
    const parts = r.stageMeanMs.slice(0, -1).reduce((sum, [, ms]) => sum + ms, 0);
    expect(parts).toBeGreaterThan(0);
    expect(parts).toBeLessThanOrEqual(meanTotal * 1.000001);
  }, 30_000);

  it("ends where stepping the same scene as many steps in one call ends (the same state hash)", () => {
    engine.loadSceneJson(SCENE);
    const measured = measureSteps(engine, 20);
    engine.loadSceneJson(SCENE);
    engine.step(20);
    expect(measured.stateHash).toBe(hashHex(engine.stateHash()));
    expect(measured.stateHash).toMatch(/^[0-9a-f]{16}$/);
    // And not where 19 steps end: the hash says which step it is.
    engine.loadSceneJson(SCENE);
    engine.step(19);
    expect(measured.stateHash).not.toBe(hashHex(engine.stateHash()));
  }, 60_000);

  it("gives each thread's part of each stage only while the engine times its threads", () => {
    engine.loadSceneJson(SCENE);
    expect(measureSteps(engine, 3).threadStages).toEqual([]);
    engine.setThreadTiming(true);
    let r;
    try {
      r = measureSteps(engine, 6);
    } finally {
      engine.setThreadTiming(false);
    }
    const total = r.threadStages.at(-1)!;
    expect(total.stage).toBe("total");
    expect(r.threadStages.map((s) => s.stage)).toContain("solve");
    // One thread (the single-threaded module): the step's thread is busy through every stage.
    expect(total.busy_ms).toHaveLength(1);
    expect(total.wall_ms).toBeCloseTo(r.stageMeanMs.at(-1)![1], 6);
    expect(total.busy_ms[0]).toBeCloseTo(total.wall_ms, 6);
    expect(total.barrier_ms[0]).toBe(0);
    expect(total.barriers).toBe(0);
  }, 30_000);

  it("refuses a window that is not a whole number of steps in range", () => {
    engine.loadSceneJson(SCENE);
    for (const bad of [0, -1, 2.5, MAX_MEASURED_STEPS + 1, Number.NaN]) {
      expect(() => measureSteps(engine, bad)).toThrow(/steps to measure: expected an integer from 1 to/);
    }
  });
});
