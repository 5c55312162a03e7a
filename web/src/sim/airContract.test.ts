// The page reads the engine's air as the engine writes it: the source rows,
// the grid's layout (x fastest, cell centres), and motes carried by the
// engine's own field move the way that field blows. Needs the wasm build.

import { beforeAll, describe, expect, it } from "vitest";
import { loadBuiltEngine } from "./builtEngine";
import { EngineError, type Engine } from "./engine";
import { AIR_GRID_STRIDE, checkAirLayout, readSources, type AirField } from "./airLayout";
import { MoteState, mulberry32, sampleField, stepMotes } from "../render/moteField";
import { fanAt } from "../ui/fanPlacement";

let engine: Engine;

beforeAll(async () => {
  engine = await loadBuiltEngine();
});

function fieldOf(e: Engine, nx: number, ny: number, nz: number): AirField {
  const { grid, cells } = e.airGrid(nx, ny, nz);
  return { dims: [nx, ny, nz], min: [...grid.min] as AirField["min"], max: [...grid.max] as AirField["max"], cells: cells.slice(), time: grid.time_s, moving: grid.moving };
}

describe("the engine's air, as the page reads it", () => {
  it("has the strides the page reads", () => {
    expect(() => checkAirLayout(engine.constants)).not.toThrow();
  });

  it("lists a placed fan as the tool asked for it, and refuses a fan outside the room", () => {
    engine.loadDefaultScene();
    expect(engine.airSources().length).toBe(0);
    engine.applyAir({ command: "add_fan", fan: fanAt([0.5, -2], 0, [0, 0, 1], 3, true) });
    const [fan] = readSources(engine.airSources());
    expect(fan.kind).toBe("fan");
    expect(fan.jet).toBe(0);
    expect(fan.outlet[0]).toBeCloseTo(0.5, 6);
    expect(fan.outlet[2]).toBeCloseTo(-2, 6);
    expect(fan.fullSpeed).toBe(3);
    expect(fan.sweep).toBeCloseTo(Math.PI / 2, 6);
    expect(() => engine.applyAir({ command: "add_fan", fan: fanAt([50, 0], 0, [0, 0, 1], 3, false) })).toThrow(EngineError);
    engine.applyAir({ command: "set_fan_speed", fan: 0, speed_m_s: 5 });
    expect(readSources(engine.airSources())[0].fullSpeed).toBe(5);
    engine.applyAir({ command: "remove_fan", fan: 0 });
    expect(engine.airSources().length).toBe(0);
    engine.applyAir({ command: "open_door", seconds: 10 });
    expect(readSources(engine.airSources())[0].kind).toBe("draught");
  });

  it("samples its field on the page's grid where the engine's points say, x fastest", () => {
    engine.loadDefaultScene();
    engine.applyAir({ command: "add_fan", fan: fanAt([0, -2.5], 0, [0, 0, 1], 3, false) });
    const field = fieldOf(engine, 12, 9, 12);
    expect(field.moving).toBe(true);
    const size = [0, 1, 2].map((a) => (field.max[a] - field.min[a]) / field.dims[a]);
    const centre = (i: number, j: number, k: number) => [field.min[0] + (i + 0.5) * size[0], field.min[1] + (j + 0.5) * size[1], field.min[2] + (k + 0.5) * size[2]];
    const picks = [[5, 3, 7], [6, 4, 9], [0, 0, 0], [11, 8, 11]];
    const at = engine.airAt(new Float32Array(picks.flatMap(([i, j, k]) => centre(i, j, k)))).slice();
    picks.forEach(([i, j, k], n) => {
      const o = ((k * 9 + j) * 12 + i) * AIR_GRID_STRIDE;
      for (let a = 0; a < 3; a++) expect(field.cells[o + a]).toBeCloseTo(at[n * 3 + a], 6);
    });
  });

  it("carries motes from the fan's outlet along its jet", () => {
    engine.loadDefaultScene();
    engine.applyAir({ command: "add_fan", fan: fanAt([0, -2.5], 0, [0, 0, 1], 3, false) });
    const sources = readSources(engine.airSources());
    const field = fieldOf(engine, 24, 18, 24);
    const u = new Float32Array(4);
    sampleField(field, 0, 1, -1.5, u);
    expect(u[2]).toBeGreaterThan(1);
    const motes = new MoteState(200);
    const random = mulberry32(7);
    for (let i = 0; i < motes.count; i++) {
      motes.position.set([0, 1, -2.4], i * 3);
      motes.life[i] = 10;
    }
    for (let f = 0; f < 30; f++) stepMotes(motes, field, sources, 1 / 60, random);
    // Half a second in a 3 m/s jet: about a metre downstream, still on its axis.
    expect(motes.position[2]).toBeGreaterThan(-2.4 + 0.6);
    expect(Math.hypot(motes.position[0], motes.position[1] - 1)).toBeLessThan(0.2);
  });
});
