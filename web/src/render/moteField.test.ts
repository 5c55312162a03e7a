import { describe, expect, it } from "vitest";
import { AIR_GRID_STRIDE, type AirField, type AirSource, type Vec3 } from "../sim/airLayout";
import { MAX_MOTE_STEP_S, MoteState, SHOWN_SPEED, STILL_SPEED, moteAlpha, mulberry32, respawn, sampleField, scatterMotes, stepMotes } from "./moteField";

/** A field on `dims` cells of the box [0, size] holding `u(centre)` at each cell's centre. */
function fieldOf(dims: Vec3, size: Vec3, u: (p: Vec3) => Vec3): AirField {
  const [nx, ny, nz] = dims;
  const cells = new Float32Array(nx * ny * nz * AIR_GRID_STRIDE);
  for (let k = 0; k < nz; k++)
    for (let j = 0; j < ny; j++)
      for (let i = 0; i < nx; i++) {
        const p: Vec3 = [((i + 0.5) * size[0]) / nx, ((j + 0.5) * size[1]) / ny, ((k + 0.5) * size[2]) / nz];
        const v = u(p);
        const o = ((k * ny + j) * nx + i) * AIR_GRID_STRIDE;
        cells.set([...v, Math.hypot(...v)], o);
      }
  return { dims, min: [0, 0, 0], max: size, cells, time: 0, moving: true };
}

const linear = (p: Vec3): Vec3 => [0.5 + 0.2 * p[0] - 0.1 * p[2], 0.3 * p[1], -0.25 + 0.05 * p[0] + 0.4 * p[2]];

describe("the field between the engine's cells", () => {
  it("is exact for a field linear in x, y and z between the cell centres (x fastest, then y, then z)", () => {
    const field = fieldOf([5, 4, 6], [3, 2, 4], linear);
    const out = new Float32Array(4);
    for (const p of [[0.4, 0.3, 0.4], [1.7, 1.1, 2.9], [2.6, 1.7, 3.6], [1.5, 1.0, 2.0]] as Vec3[]) {
      expect(sampleField(field, ...p, out)).toBe(true);
      const u = linear(p);
      for (let a = 0; a < 3; a++) expect(out[a]).toBeCloseTo(u[a], 5);
      expect(out[3]).toBeCloseTo(Math.hypot(...u), 5);
    }
  });

  it("holds the outermost centres' values out to the box's faces, and is zero outside it", () => {
    const field = fieldOf([4, 4, 4], [2, 2, 2], linear);
    const out = new Float32Array(4);
    const atCorner = new Float32Array(4);
    sampleField(field, 0.25, 0.25, 0.25, atCorner);
    expect(sampleField(field, 0, 0, 0, out)).toBe(true);
    expect(Array.from(out)).toEqual(Array.from(atCorner));
    expect(sampleField(field, -0.01, 1, 1, out)).toBe(false);
    expect(Array.from(out)).toEqual([0, 0, 0, 0]);
  });

  it("reads a grid one cell thick along an axis", () => {
    const field = fieldOf([3, 1, 3], [3, 1, 3], () => [1, 2, 3]);
    const out = new Float32Array(4);
    expect(sampleField(field, 1.2, 0.9, 2.2, out)).toBe(true);
    expect(Array.from(out.subarray(0, 3))).toEqual([1, 2, 3]);
  });
});

const fan: AirSource = { kind: "fan", jet: 0, outlet: [1, 1, 1], aim: [0, 0, 1], speed: 3, fullSpeed: 3, diameter: 0.4, sweep: 0 };

describe("motes", () => {
  it("move with a uniform stream by u·dt a frame, a long frame cut to the longest step", () => {
    const field = fieldOf([4, 4, 4], [4, 4, 4], () => [1, 0, -0.5]);
    const motes = new MoteState(50);
    const random = mulberry32(1);
    scatterMotes(motes, field, [], random);
    for (let i = 0; i < motes.count; i++) {
      motes.age[i] = 0;
      motes.life[i] = 100;
      motes.position.set([2, 2, 2], i * 3);
    }
    stepMotes(motes, field, [], 0.02, random);
    expect(motes.position[0]).toBeCloseTo(2.02, 6);
    expect(motes.position[2]).toBeCloseTo(1.99, 6);
    expect(motes.speed[0]).toBeCloseTo(Math.hypot(1, 0.5), 6);
    stepMotes(motes, field, [], 1, random);
    expect(motes.position[0]).toBeCloseTo(2.02 + MAX_MOTE_STEP_S, 5);
    expect(motes.age[0]).toBeCloseTo(0.02 + MAX_MOTE_STEP_S, 6);
  });

  it("start again at the end of their life or outside the room", () => {
    const field = fieldOf([4, 4, 4], [4, 4, 4], () => [10, 0, 0]);
    const motes = new MoteState(2);
    const random = mulberry32(2);
    scatterMotes(motes, field, [], random);
    motes.position.set([3.99, 2, 2, 1, 1, 1], 0);
    motes.age.set([0, 9]);
    motes.life.set([5, 9]);
    stepMotes(motes, field, [], 0.01, random);
    // The second's life ended: it starts afresh; the first left the box in its step.
    expect(motes.age[1]).toBe(0);
    expect(motes.position[0]).toBeGreaterThan(4);
    // The first's next step starts it afresh.
    stepMotes(motes, field, [], 0.01, random);
    expect(motes.age[0]).toBe(0);
    for (let i = 0; i < 6; i++) expect(motes.position[i]).toBeGreaterThanOrEqual(0);
  });

  it("start at a blowing outlet's disc, or anywhere in the room", () => {
    const field = fieldOf([4, 4, 4], [4, 4, 4], () => [0, 0, 0]);
    const motes = new MoteState(2000);
    const random = mulberry32(3);
    let atOutlet = 0;
    for (let i = 0; i < motes.count; i++) {
      respawn(motes, i, field, [fan], random);
      const [x, y, z] = motes.position.subarray(i * 3, i * 3 + 3);
      const onDisc = Math.abs(z - 1) < 1e-6 && Math.hypot(x - 1, y - 1) <= 0.2 + 1e-6;
      if (onDisc) atOutlet++;
      else for (const c of [x, y, z]) expect(c >= 0 && c <= 4).toBe(true);
      expect(motes.life[i]).toBeGreaterThan(0);
    }
    expect(atOutlet / motes.count).toBeGreaterThan(0.5);
    expect(atOutlet / motes.count).toBeLessThan(0.7);
    // A fan that does not blow starts none.
    respawn(motes, 0, field, [], random);
    expect(Math.abs(motes.position[2] - 1) < 1e-6 && Math.hypot(motes.position[0] - 1, motes.position[1] - 1) <= 0.2).toBe(false);
  });

  it("show where the air moves, fading in and out over their life", () => {
    expect(moteAlpha(2, 4, STILL_SPEED)).toBe(0);
    expect(moteAlpha(2, 4, SHOWN_SPEED)).toBe(1);
    expect(moteAlpha(0, 4, 3)).toBe(0);
    expect(moteAlpha(0.4, 4, 3)).toBeCloseTo(0.5, 9);
    expect(moteAlpha(4, 4, 3)).toBe(0);
  });
});

describe("the first motes", () => {
  it("are already carried along the jet for the age they start at", () => {
    const field = fieldOf([8, 8, 8], [4, 4, 4], (p) => (Math.hypot(p[0] - 1, p[1] - 1) < 0.6 && p[2] > 1 ? [0, 0, 1] : [0, 0, 0]));
    const motes = new MoteState(1000);
    scatterMotes(motes, field, [fan], mulberry32(5));
    let downstream = 0;
    for (let i = 0; i < motes.count; i++) {
      const [x, y, z] = motes.position.subarray(i * 3, i * 3 + 3);
      if (Math.hypot(x - 1, y - 1) < 0.2 && z > 1.5) downstream++;
    }
    // Six in ten start on the outlet; most of those have aged past half a metre of the stream.
    expect(downstream / motes.count).toBeGreaterThan(0.25);
  });
});
