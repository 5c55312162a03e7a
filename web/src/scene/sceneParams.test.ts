import { beforeAll, describe, expect, it } from "vitest";
import { loadBuiltEngine } from "../sim/builtEngine";
import type { Engine } from "../sim/engine";
import { applyParams, paramsFromScene, splitCount } from "./sceneParams";
import { filledScene, setEngineConstants, type Scene } from "./sceneSchema";

let engine: Engine;

beforeAll(async () => {
  engine = await loadBuiltEngine();
  setEngineConstants(engine.constants, engine.defaultSceneJson());
});

const scene: Scene = {
  room: { width: 6, depth: 5, wall_height: 3, ceiling: "pyramid", apex_height: 1.5 },
  balloons: [
    { count: 30, colors: ["red"], size_in: 11, spawn: { min: [-1, 0, -1], max: [1, 1, 1] } },
    { count: 20, colors: ["blue"], size_in: 11, gas: "helium" },
  ],
  air: { temperature_c: 20, pressure_kpa: 101.325 },
  sim: { seed: 3, substeps: 4, friction: 0.5, restitution: 0.4, drag_coefficient: 0.95 },
};

describe("panel parameters", () => {
  it("reads the parameters from a scene, missing keys as the engine reads them", () => {
    const p = paramsFromScene(scene);
    expect(p).toMatchObject({ count: 50, sizeIn: 11, helium: true, width: 6, depth: 5, ceiling: "pyramid", substeps: 4 });
    // The empty scene is the engine's default scene, key for key.
    const engineDefault = JSON.parse(engine.defaultSceneJson()) as Scene;
    expect(paramsFromScene({})).toEqual(paramsFromScene(engineDefault));
    const d = filledScene({});
    expect(paramsFromScene({})).toMatchObject({ width: d.room.width, wallHeight: d.room.wall_height, drag: d.sim.drag_coefficient, substeps: d.sim.substeps });
    // A section given in part keeps the engine's default for the rest.
    expect(paramsFromScene({ room: { width: 9 } })).toMatchObject({ width: 9, depth: d.room.depth, apexHeight: d.room.apex_height });
  });

  it("writes them back, keeping the other keys, and the result is valid", () => {
    const p = { ...paramsFromScene(scene), count: 7, sizeIn: 16, helium: false, ceiling: "flat" as const, friction: 0.2 };
    const out = applyParams(scene, p);
    const groups = out.balloons!;
    expect(groups.map((g) => g.count)).toEqual([4, 3]);
    expect(groups[0].diameter_m).toBeCloseTo(0.4064, 4);
    expect(groups[0].size_in).toBeUndefined();
    expect(groups[0].spawn).toBeUndefined();
    expect(groups[1].gas).toBe("air");
    expect(groups[0].colors).toEqual(["red"]);
    expect(out.sim?.seed).toBe(3);
    expect(out.sim?.friction).toBe(0.2);
    expect(out.room?.ceiling).toBe("flat");
    expect(engine.validateScene(JSON.stringify(out))).toBeNull();
    // The input is untouched.
    expect(scene.balloons![0].count).toBe(30);
  });

  it("round-trips: reading what was written gives the same parameters", () => {
    const p = { ...paramsFromScene(scene), count: 123, width: 8, apexHeight: 2 };
    expect(paramsFromScene(applyParams(scene, p))).toEqual(p);
  });

  it("keeps the live settings a scene carries (ribbons, gravity) when the panel rebuilds it", () => {
    const live: Scene = { ...scene, balloons: [{ count: 2, ribbon: { length_m: 1.5, color: "red", segments: 8 } }], sim: { gravity: [0, -1.62, 0] } };
    const out = applyParams(live, { ...paramsFromScene(live), count: 5 });
    expect(out.balloons![0].ribbon).toEqual({ length_m: 1.5, color: "red", segments: 8 });
    expect(out.sim?.gravity).toEqual([0, -1.62, 0]);
  });

  it("splits a total over groups like the CLI", () => {
    expect(splitCount(10, 3)).toEqual([4, 3, 3]);
    expect(splitCount(2, 3)).toEqual([1, 1, 0]);
    expect(splitCount(5, 0)).toEqual([5]);
  });
});
