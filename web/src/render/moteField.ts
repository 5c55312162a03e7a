// Motes carried by the air, as pure maths over typed arrays: the field's
// value at a point (trilinear between the centres of the engine's grid
// cells), one Euler step of every mote through it, and where a mote starts
// again when its life ends or it leaves the room (half of them at an
// outlet, so that the jets fill with them; the rest anywhere in the room).
// Positions live on the CPU and persist from frame to frame, so a mote
// traces a path line of the changing field; a few thousand cost a fraction
// of a millisecond a frame (docs/perf-log.md).

import { AIR_GRID_STRIDE, type AirField, type AirSource } from "../sim/airLayout";

/** A mote's life, s: long enough to cross a jet, short enough that the room keeps being sampled. */
export const MOTE_LIFE_S: [number, number] = [2.5, 5];
/** Share of motes that start at an outlet while any source blows. */
export const OUTLET_SHARE = 0.6;
/** Longest step a mote takes at once, s (a frame after a stall does not fling motes): 30 cm in a 3 m/s jet, about a cell. */
export const MAX_MOTE_STEP_S = 0.1;

/**
 * The field at (x, y, z), m/s, into `out` (ux, uy, uz, |u|): trilinear
 * between cell centres, constant from the outermost centres to the box's
 * faces. Returns false (and zeros) outside the box.
 */
export function sampleField(field: AirField, x: number, y: number, z: number, out: Float32Array | number[]): boolean {
  const min = field.min;
  const max = field.max;
  if (!(x >= min[0] && x <= max[0] && y >= min[1] && y <= max[1] && z >= min[2] && z <= max[2])) {
    out[0] = out[1] = out[2] = out[3] = 0;
    return false;
  }
  const dims = field.dims;
  const cells = field.cells;
  const nx = dims[0];
  const ny = dims[1];
  const nz = dims[2];
  // Continuous cell coordinates, 0 at the first cell's centre, clamped to the outermost centres.
  let gx = ((x - min[0]) * nx) / (max[0] - min[0]) - 0.5;
  let gy = ((y - min[1]) * ny) / (max[1] - min[1]) - 0.5;
  let gz = ((z - min[2]) * nz) / (max[2] - min[2]) - 0.5;
  gx = gx < 0 ? 0 : gx > nx - 1 ? nx - 1 : gx;
  gy = gy < 0 ? 0 : gy > ny - 1 ? ny - 1 : gy;
  gz = gz < 0 ? 0 : gz > nz - 1 ? nz - 1 : gz;
  // The lower corner (one short of the last cell, so its upper neighbour exists), and the step to the upper one.
  let i0 = gx | 0;
  let j0 = gy | 0;
  let k0 = gz | 0;
  if (i0 > nx - 2) i0 = nx > 1 ? nx - 2 : 0;
  if (j0 > ny - 2) j0 = ny > 1 ? ny - 2 : 0;
  if (k0 > nz - 2) k0 = nz > 1 ? nz - 2 : 0;
  const fx = gx - i0;
  const fy = gy - j0;
  const fz = gz - k0;
  const di = nx > 1 ? AIR_GRID_STRIDE : 0;
  const dj = ny > 1 ? nx * AIR_GRID_STRIDE : 0;
  const dk = nz > 1 ? nx * ny * AIR_GRID_STRIDE : 0;
  const a = ((k0 * ny + j0) * nx + i0) * AIR_GRID_STRIDE;
  const b = a + dj;
  const c = a + dk;
  const d = c + dj;
  // Weights of the eight corners.
  const gx1 = 1 - fx;
  const gy1 = 1 - fy;
  const gz1 = 1 - fz;
  const w000 = gx1 * gy1 * gz1;
  const w100 = fx * gy1 * gz1;
  const w010 = gx1 * fy * gz1;
  const w110 = fx * fy * gz1;
  const w001 = gx1 * gy1 * fz;
  const w101 = fx * gy1 * fz;
  const w011 = gx1 * fy * fz;
  const w111 = fx * fy * fz;
  // Unrolled by hand: this runs for every mote every other frame.
  const u = w000 * cells[a] + w100 * cells[a + di] + w010 * cells[b] + w110 * cells[b + di] + w001 * cells[c] + w101 * cells[c + di] + w011 * cells[d] + w111 * cells[d + di];
  const v = w000 * cells[a + 1] + w100 * cells[a + di + 1] + w010 * cells[b + 1] + w110 * cells[b + di + 1] + w001 * cells[c + 1] + w101 * cells[c + di + 1] + w011 * cells[d + 1] + w111 * cells[d + di + 1];
  const w = w000 * cells[a + 2] + w100 * cells[a + di + 2] + w010 * cells[b + 2] + w110 * cells[b + di + 2] + w001 * cells[c + 2] + w101 * cells[c + di + 2] + w011 * cells[d + 2] + w111 * cells[d + di + 2];
  out[0] = u;
  out[1] = v;
  out[2] = w;
  out[3] = Math.sqrt(u * u + v * v + w * w);
  return true;
}

/** A small fast generator (mulberry32): the same motes from the same seed, no allocation. */
export function mulberry32(seed: number): () => number {
  let a = seed >>> 0;
  return () => {
    a = (a + 0x6d2b79f5) >>> 0;
    let t = a;
    t = Math.imul(t ^ (t >>> 15), t | 1);
    t ^= t + Math.imul(t ^ (t >>> 7), t | 61);
    return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
  };
}

/** Every mote's state, structure of arrays. */
export class MoteState {
  /** x, y, z per mote, m. */
  readonly position: Float32Array;
  /** The air's velocity where each mote was last moved, m/s (x, y, z), and its speed. */
  readonly velocity: Float32Array;
  readonly speed: Float32Array;
  /** Seconds lived, and the life it has, s. */
  readonly age: Float32Array;
  readonly life: Float32Array;

  constructor(readonly count: number) {
    this.position = new Float32Array(count * 3);
    this.velocity = new Float32Array(count * 3);
    this.speed = new Float32Array(count);
    this.age = new Float32Array(count);
    this.life = new Float32Array(count);
  }
}

/** The sources motes start at: those that blow now. */
function blowing(sources: readonly AirSource[]): AirSource[] {
  return sources.filter((s) => s.speed > 0);
}

/**
 * Starts mote `i` afresh: at a random point of a random blowing source's
 * outlet disc (with `OUTLET_SHARE`), else anywhere in the field's box; a
 * fresh life, age 0 (or a random age, `scatter`, so that a first start is not in step).
 */
export function respawn(motes: MoteState, i: number, field: AirField, outlets: readonly AirSource[], random: () => number, scatter = false): void {
  const p = motes.position;
  const o = i * 3;
  if (outlets.length > 0 && random() < OUTLET_SHARE) {
    const s = outlets[Math.min(outlets.length - 1, Math.floor(random() * outlets.length))];
    // Two unit vectors across the aim (u = aim × a helper axis, v = aim × u), then a uniform point of the disc.
    const [ax, ay, az] = s.aim;
    const hx = Math.abs(ax) < 0.9 ? 1 : 0;
    const hy = 1 - hx;
    let ux = -az * hy;
    let uy = az * hx;
    let uz = ax * hy - ay * hx;
    const ul = Math.hypot(ux, uy, uz) || 1;
    ux /= ul;
    uy /= ul;
    uz /= ul;
    const vx = ay * uz - az * uy;
    const vy = az * ux - ax * uz;
    const vz = ax * uy - ay * ux;
    const r = 0.5 * s.diameter * Math.sqrt(random());
    const angle = 2 * Math.PI * random();
    const c = r * Math.cos(angle);
    const d = r * Math.sin(angle);
    p[o] = s.outlet[0] + c * ux + d * vx;
    p[o + 1] = s.outlet[1] + c * uy + d * vy;
    p[o + 2] = s.outlet[2] + c * uz + d * vz;
  } else {
    for (let a = 0; a < 3; a++) p[o + a] = field.min[a] + random() * (field.max[a] - field.min[a]);
  }
  const [lo, hi] = MOTE_LIFE_S;
  motes.life[i] = lo + random() * (hi - lo);
  motes.age[i] = scatter ? random() * motes.life[i] : 0;
  motes.velocity[o] = motes.velocity[o + 1] = motes.velocity[o + 2] = 0;
  motes.speed[i] = 0;
}

const sample = new Float32Array(4);

/**
 * Starts every mote afresh at a scattered age, and carries each through the
 * field for the age it was given (steps of `MAX_MOTE_STEP_S`), so that the
 * jets are full from the first frame rather than filling over seconds.
 */
export function scatterMotes(motes: MoteState, field: AirField, sources: readonly AirSource[], random: () => number): void {
  const outlets = blowing(sources);
  const p = motes.position;
  for (let i = 0; i < motes.count; i++) {
    respawn(motes, i, field, outlets, random, true);
    const o = i * 3;
    for (let t = 0; t < motes.age[i]; t += MAX_MOTE_STEP_S) {
      if (!sampleField(field, p[o], p[o + 1], p[o + 2], sample)) {
        respawn(motes, i, field, outlets, random);
        break;
      }
      p[o] += sample[0] * MAX_MOTE_STEP_S;
      p[o + 1] += sample[1] * MAX_MOTE_STEP_S;
      p[o + 2] += sample[2] * MAX_MOTE_STEP_S;
    }
  }
}

/**
 * Moves motes `from` to `to` (all by default) `dt` seconds (at most
 * `MAX_MOTE_STEP_S`) along the field (one Euler step: the field is smooth on
 * the scale a mote moves in a frame or two) and starts again those whose
 * life ended or that left the box.
 */
export function stepMotes(motes: MoteState, field: AirField, sources: readonly AirSource[], dt: number, random: () => number, from = 0, to = motes.count): void {
  const h = Math.min(Math.max(dt, 0), MAX_MOTE_STEP_S);
  const p = motes.position;
  const v = motes.velocity;
  let outlets: AirSource[] | null = null;
  for (let i = from; i < to; i++) {
    const o = i * 3;
    motes.age[i] += h;
    const inside = sampleField(field, p[o], p[o + 1], p[o + 2], sample);
    if (!inside || motes.age[i] >= motes.life[i]) {
      outlets ??= blowing(sources);
      respawn(motes, i, field, outlets, random);
      continue;
    }
    v[o] = sample[0];
    v[o + 1] = sample[1];
    v[o + 2] = sample[2];
    motes.speed[i] = sample[3];
    p[o] += sample[0] * h;
    p[o + 1] += sample[1] * h;
    p[o + 2] += sample[2] * h;
  }
}

/** Below this speed a mote is not drawn, m/s (still air shows nothing); it is fully drawn from `SHOWN_SPEED`. */
export const STILL_SPEED = 0.05;
export const SHOWN_SPEED = 0.4;

/**
 * How visible a mote is, 0–1: faded in and out over the first and last
 * fifth of its life, and by the air's speed where it is.
 */
export function moteAlpha(age: number, life: number, speed: number): number {
  const t = life > 0 ? age / life : 1;
  const fade = Math.min(1, Math.max(0, Math.min(t, 1 - t) * 5));
  const s = Math.min(1, Math.max(0, (speed - STILL_SPEED) / (SHOWN_SPEED - STILL_SPEED)));
  return fade * s;
}
