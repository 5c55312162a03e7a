// "Show air": a few thousand motes carried by the engine's field, drawn as
// short streaks (tail = where the air would have brought the mote from a
// moment ago, so the streak's length is the air's speed) with a bright head.
// The motes move on the CPU through the field the worker samples on a coarse
// grid every quarter second (moteField.ts: one trilinear lookup and one
// Euler step a mote), half of them each frame by the time since their last
// move (each mote moves 30 times a second at 60 frames a second: half the
// frame's work, and half the upload, for a motion the eye reads as smooth);
// the GPU draws them from two buffers in two draw calls (the streaks as
// lines, their heads as points of the same vertices). Motes in still air are
// not drawn, so a room without moving air shows nothing.

import * as THREE from "three";
import type { AirField, AirSource } from "../sim/airLayout";
import { MoteState, moteAlpha, mulberry32, scatterMotes, stepMotes } from "./moteField";

/** Motes drawn: enough to fill two or three jets, a fraction of a millisecond to move (docs/perf-log.md). */
export const MOTE_COUNT = 3000;
/** A streak spans the path of the last this many seconds, s. */
export const STREAK_S = 0.15;
/** Head point size, CSS pixels. */
const POINT_PX = 2.5;

/** A mote's colour at `speed` (m/s), 0–255 RGB into `out`: pale blue in a breeze, white in a jet. */
export function moteColor(speed: number, out: Uint8Array, o: number): void {
  const t = Math.min(1, speed / 3);
  out[o] = 150 + 105 * t;
  out[o + 1] = 200 + 55 * t;
  out[o + 2] = 255;
}

export class AirMotes {
  readonly group = new THREE.Group();
  readonly motes: MoteState;
  private field: AirField | null = null;
  private seeded = false;
  private readonly random = mulberry32(0x5eed);
  /** Two vertices a mote (head, tail): x, y, z each. */
  private readonly positions: Float32Array;
  /** RGBA a vertex, 0–255. */
  private readonly colors: Uint8Array;
  private readonly geometry = new THREE.BufferGeometry();
  private readonly positionAttribute: THREE.BufferAttribute;
  private readonly colorAttribute: THREE.BufferAttribute;
  /** Motes drawn (alpha above zero) among those written last, times the halves. */
  visibleCount = 0;
  /** Which half moves this frame, and the seconds each half has not yet moved. */
  private half = 0;
  private readonly pending = [0, 0];
  private readonly visibleByHalf = [0, 0];

  constructor(count = MOTE_COUNT) {
    this.group.name = "air-motes";
    this.group.visible = false;
    this.motes = new MoteState(count);
    this.positions = new Float32Array(count * 6);
    this.colors = new Uint8Array(count * 8);
    this.positionAttribute = new THREE.BufferAttribute(this.positions, 3).setUsage(THREE.DynamicDrawUsage);
    this.colorAttribute = new THREE.BufferAttribute(this.colors, 4, true).setUsage(THREE.DynamicDrawUsage);
    this.geometry.setAttribute("position", this.positionAttribute);
    this.geometry.setAttribute("color", this.colorAttribute);
    // The motes fill the room: no bounds to cull by.
    const common = { vertexColors: true, transparent: true, depthWrite: false, toneMapped: false } as const;
    const lines = new THREE.LineSegments(this.geometry, new THREE.LineBasicMaterial(common));
    const heads = new THREE.Points(this.geometry, new THREE.PointsMaterial({ ...common, size: POINT_PX, sizeAttenuation: false }));
    for (const o of [lines, heads]) {
      o.frustumCulled = false;
      o.renderOrder = 5;
      this.group.add(o);
    }
  }

  get shown(): boolean {
    return this.group.visible;
  }

  /** Shown or not; hidden motes cost nothing a frame. */
  setShown(on: boolean): void {
    this.group.visible = on;
    if (!on) this.visibleCount = 0;
  }

  /** A new field from the worker; the first one places every mote. */
  setField(field: AirField): void {
    this.field = field;
  }

  /** A new world: the motes start afresh with its first field. */
  reset(): void {
    this.field = null;
    this.seeded = false;
  }

  /** Moves the motes `dt` seconds through the newest field and writes their streaks. */
  update(sources: readonly AirSource[], dt: number): void {
    const field = this.field;
    if (!this.group.visible || !field) return;
    const motes = this.motes;
    let from = 0;
    let to = motes.count;
    this.pending[0] += dt;
    this.pending[1] += dt;
    if (!this.seeded) {
      scatterMotes(motes, field, sources, this.random);
      this.seeded = true;
      this.pending[0] = this.pending[1] = 0;
    } else {
      const split = Math.ceil(motes.count / 2);
      [from, to] = this.half === 0 ? [0, split] : [split, motes.count];
    }
    if (!field.moving) {
      // Still air: nothing to draw, nothing to move.
      if (this.visibleCount > 0) {
        this.colors.fill(0);
        this.colorAttribute.clearUpdateRanges();
        this.colorAttribute.needsUpdate = true;
      }
      this.visibleCount = 0;
      this.visibleByHalf.fill(0);
      return;
    }
    const moved = this.half;
    stepMotes(motes, field, sources, this.pending[moved], this.random, from, to);
    this.pending[moved] = 0;
    this.half = 1 - moved;
    const p = motes.position;
    const v = motes.velocity;
    const out = this.positions;
    const c = this.colors;
    let visible = 0;
    for (let i = from; i < to; i++) {
      const o = i * 3;
      const w = i * 6;
      out[w] = p[o];
      out[w + 1] = p[o + 1];
      out[w + 2] = p[o + 2];
      out[w + 3] = p[o] - v[o] * STREAK_S;
      out[w + 4] = p[o + 1] - v[o + 1] * STREAK_S;
      out[w + 5] = p[o + 2] - v[o + 2] * STREAK_S;
      const alpha = moteAlpha(motes.age[i], motes.life[i], motes.speed[i]);
      const k = i * 8;
      moteColor(motes.speed[i], c, k);
      c[k + 3] = 255 * alpha;
      c[k + 4] = c[k];
      c[k + 5] = c[k + 1];
      c[k + 6] = c[k + 2];
      c[k + 7] = 0;
      if (alpha > 0) visible++;
    }
    if (to - from === motes.count) this.visibleByHalf.fill(visible / 2);
    else this.visibleByHalf[moved] = visible;
    this.visibleCount = Math.round(this.visibleByHalf[0] + this.visibleByHalf[1]);
    // Only the moved motes' vertices go to the GPU.
    for (const [attribute, floats] of [
      [this.positionAttribute, 6],
      [this.colorAttribute, 8],
    ] as const) {
      attribute.clearUpdateRanges();
      attribute.addUpdateRange(from * floats, (to - from) * floats);
      attribute.needsUpdate = true;
    }
  }
}
