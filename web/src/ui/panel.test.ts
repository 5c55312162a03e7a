// The panel's live lines: each sends one typed `LiveSetting` the engine
// takes as it is, reads its value from the engine's scene, and offers the
// engine's range. Needs the wasm build.

import { beforeAll, describe, expect, it } from "vitest";
import { loadBuiltEngine } from "../sim/builtEngine";
import type { Engine, LiveSetting, Scene } from "../sim/engine";
import { setEngineConstants } from "../scene/sceneSchema";
import { LIVE_LINES, liveSetting, sliderRange } from "./panel";

let engine: Engine;

beforeAll(async () => {
  engine = await loadBuiltEngine();
  setEngineConstants(engine.constants, engine.defaultSceneJson());
});

describe("live lines", () => {
  it("each line's value is sent as { control, value }, the engine's LiveSetting", () => {
    const gravity: LiveSetting = liveSetting("gravity", 1.62);
    expect(gravity).toEqual({ control: "gravity", value: 1.62 });
    for (const line of LIVE_LINES) expect(liveSetting(line.control, 0.5)).toEqual({ control: line.control, value: 0.5 });
  });

  it("the engine takes what each line sends, and the line reads it back from the engine's scene", () => {
    for (const line of LIVE_LINES) {
      engine.loadDefaultScene();
      const { min, max } = sliderRange(line, engine.constants);
      const value = Math.round(((min + max) / 3) * 100) / 100;
      engine.applyLive(liveSetting(line.control, value));
      const scene = JSON.parse(engine.sceneJson()) as Scene;
      expect(line.read(scene), line.control).toBeCloseTo(value, 5);
    }
  });

  it("reads the default scene's values and offers at most the engine's range", () => {
    const scene = JSON.parse(engine.defaultSceneJson()) as Scene;
    const byControl = Object.fromEntries(LIVE_LINES.map((l) => [l.control, l]));
    expect(byControl.gravity.read(scene)).toBeCloseTo(9.81, 5);
    expect(byControl.gravity.read({}), "a scene without gravity has the engine's").toBeCloseTo(9.81, 5);
    engine.loadDefaultScene();
    expect(byControl.ribbon_length.read(scene)).toBe(engine.ribbonLength());
    for (const line of LIVE_LINES) {
      const engineRange = engine.constants.live.find((r) => r.control === line.control)!;
      const { min, max } = sliderRange(line, engine.constants);
      expect(min).toBe(engineRange.min);
      expect(max).toBeLessThanOrEqual(engineRange.max);
      expect(line.read(scene)).toBeGreaterThanOrEqual(min);
      expect(line.read(scene)).toBeLessThanOrEqual(max);
    }
    expect(() => sliderRange({ ...LIVE_LINES[0], control: "wind" as LiveSetting["control"] }, engine.constants)).toThrow(/no live setting "wind"/);
  });
});
