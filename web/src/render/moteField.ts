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
/** Longest step taken in one frame, s (a frame after a stall does not fling motes). */
export const MAX_MOTE_STEP_S = 0.05;

/**
 * The field at (x, y, z), m/s, into `out` (ux, uy, uz, |u|): trilinear
 * between cell centres, constant from the outermost centres to the box's
 * faces. Returns false (and zeros) outside the box.
 */
export function sampleField(field: AirField, x: number, y: number, z: number, out: Float32Array | number[]): boolean {
  const { dims, min, max, cells } = field;
  const inside = x >= min[0] && x <= max[0] && y >= min[1] && y <= max[1] && z >= min[2] && z <= max[2];
  if (!inside) {
    out[0] = out[1] = out[2] = out[3] = 0;
    return false;
  }
  const nx = dims[0];
  const ny = dims[1];
  const nz = dims[2];
  // Continuous cell coordinates, 0 at the first cell's centre.
  const gx = Math.min(Math.max(((x - min[0]) / (max[0] - min[0])) * nx - 0.5, 0), nx - 1);
  const gy = Math.min(Math.max(((y - min[1]) / (max[1] - min[1])) * ny - 0.5, 0), ny - 1);
  const gz = Math.min(Math.max(((z - min[2]) / (max[2] - min[2])) * nz - 0.5, 0), nz - 1);
  const i0 = Math.min(Math.floor(gx), nx - 2 < 0 ? 0 : nx - 2);
  const j0 = Math.min(Math.floor(gy), ny - 2 < 0 ? 0 : ny - 2);
  const k0 = Math.min(Math.floor(gz), nz - 2 < 0 ? 0 : nz - 2);
  const fx = nx > 1 ? gx - i0 : 0;
  const fy = ny > 1 ? gy - j0 : 0;
  const fz = nz > 1 ? gz - k0 : 0;
  const di = nx > 1 ? AIR_GRID_STRIDE : 0;
  const dj = ny > 1 ? nx * AIR_GRID_STRIDE : 0;
  const dk = nz > 1 ? nx * ny * AIR_GRID_STRIDE : 0;
  const base = ((k0 * ny + j0) * nx + i0) * AIR_GRID_STRIDE;
  for (let c = 0; c < 3; c++) {
    const o = base + c;
    const x00 = cells[o] + (cells[o + di] - cells[o]) * fx;
    const x10 = cells[o + dj] + (cells[o + dj + di] - cells[o + dj]) * fx;
    const x01 = cells[o + dk] + (cells[o + dk + di] - cells[o + dk]) * fx;
    const x11 = cells[o + dk + dj] + (cells[o + dk + dj + di] - cells[o + dk + dj]) * fx;
    const y0 = x00 + (x10 - x00) * fy;
    const y1 = x01 + (x11 - x01) * fy;
    out[c] = y0 + (y1 - y0) * fz;
  }
  out[3] = Math.hypot(out[0], out[1], out[2]);
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

/** Starts every mote afresh, at scattered ages. */
export function scatterMotes(motes: MoteState, field: AirField, sources: readonly AirSource[], random: () => number): void {
  const outlets = blowing(sources);
  for (let i = 0; i < motes.count; i++) respawn(motes, i, field, outlets, random, true);
}

const sample = new Float32Array(4);

/**
 * Moves every mote `dt` seconds (at most `MAX_MOTE_STEP_S`) along the field
 * (one Euler step: the field is smooth on the scale a mote moves in a
 * frame) and starts again those whose life ended or that left the box.
 */
export function stepMotes(motes: MoteState, field: AirField, sources: readonly AirSource[], dt: number, random: () => number): void {
  const h = Math.min(Math.max(dt, 0), MAX_MOTE_STEP_S);
  const p = motes.position;
  const v = motes.velocity;
  let outlets: AirSource[] | null = null;
  for (let i = 0; i < motes.count; i++) {
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
