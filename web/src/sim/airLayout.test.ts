import { describe, expect, it } from "vitest";
import { AIR_GRID_STRIDE, AIR_SOURCE_STRIDE, airGridDims, checkAirLayout, readSources } from "./airLayout";
import { AIR_FIELD_INTERVAL_MS, AirSampler, roomBox } from "./airSampler";
import type { Engine } from "./engine";

describe("the air's rows", () => {
  it("read each source, naming fans and vents by their index among the jets", () => {
    const rows = new Float32Array([
      ...[0, 1, 1, -2, 0, 0, 1, 1.5, 3, 0.4, 1.57, 12],
      ...[2, 0, 1, 2.95, 0, 0, -1, 0.8, 0.8, 1.5, 0, 0],
      ...[1, 0, 3, 0, 0, -1, 0, 2, 2, 0.3, 0, 0],
    ]);
    const sources = readSources(rows);
    expect(sources.map((s) => [s.kind, s.jet])).toEqual([
      ["fan", 0],
      ["draught", -1],
      ["vent", 1],
    ]);
    expect(sources[0]).toMatchObject({ outlet: [1, 1, -2], aim: [0, 0, 1], fullSpeed: 3, diameter: expect.closeTo(0.4, 6), sweep: expect.closeTo(1.57, 5) });
    expect(sources[0].speed).toBe(1.5);
    expect(readSources(new Float32Array(AIR_SOURCE_STRIDE - 1))).toEqual([]);
  });

  it("are refused at start when the engine writes other strides", () => {
    const air = { source_stride: AIR_SOURCE_STRIDE, grid_stride: AIR_GRID_STRIDE };
    expect(() => checkAirLayout({ air } as never)).not.toThrow();
    expect(() => checkAirLayout({ air: { ...air, grid_stride: 3 } } as never)).toThrow(/air cell/);
  });
});

describe("the air's grid", () => {
  it("has cells of about a quarter metre, at least two and at most its cap along an axis", () => {
    expect(airGridDims([6, 4.5, 6])).toEqual([24, 18, 24]);
    expect(airGridDims([0.3, 40, 6])).toEqual([2, 32, 24]);
    expect(airGridDims([6, 6, 6], 0.5, 8)).toEqual([8, 8, 8]);
  });

  it("is sampled at most every interval while shown, and a still room is sent once", () => {
    const calls: number[][] = [];
    let moving = false;
    const engine = {
      airGrid: (nx: number, ny: number, nz: number) => {
        calls.push([nx, ny, nz]);
        return { grid: { dims: [nx, ny, nz], min: [-3, 0, -3], max: [3, 4.5, 3], time_s: 1, moving }, cells: new Float32Array(nx * ny * nz * 4) };
      },
    } as unknown as Engine;
    const sampler = new AirSampler();
    sampler.worldRebuilt([-3, 0, -3, 3, 4.5, 3]);
    expect(sampler.sample(engine, 0)).toBeNull();
    sampler.setShow(true);
    const still = sampler.sample(engine, 0)!;
    expect(still.dims).toEqual([24, 18, 24]);
    expect(still.moving).toBe(false);
    expect(sampler.sample(engine, AIR_FIELD_INTERVAL_MS / 2)).toBeNull();
    expect(sampler.sample(engine, AIR_FIELD_INTERVAL_MS * 2)).toBeNull();
    moving = true;
    sampler.changed();
    expect(sampler.sample(engine, AIR_FIELD_INTERVAL_MS * 2)!.moving).toBe(true);
    expect(calls.length).toBe(3);
  });

  it("tiles the box round the room's vertices", () => {
    expect(roomBox([-3, 0, -2, 3, 4.5, 2, 0, 3, 0])).toEqual({ min: [-3, 0, -2], max: [3, 4.5, 2] });
  });
});
