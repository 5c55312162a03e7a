// The forces the engine recorded over the last step, as the frame carries them:
// the worker side of probing (what to ask the engine to record, following the
// selected balloon as bodies come and go) and the reading of one body's row.
// The numbers are the engine's (`Engine::write_forces`), never recomputed here.

import type { BodyCard } from "./engine";
import type { ForceStride } from "../../public/wasm/up_wasm";

/**
 * Floats per body in the engine's force rows (`constants().force_floats`):
 * index, then weight, buoyancy, drag, contact, ribbon, other (N, x y z each),
 * centre of mass, centre of buoyancy, knot (m, x y z each; NaN without a ribbon).
 * Typed by the module's .d.ts (`ForceStride`): a page built against another layout does not compile.
 */
export const FORCE_FLOATS: ForceStride = 28;

/** Throws unless the engine writes force rows of `FORCE_FLOATS` floats: a page built against another engine says so at start. */
export function checkForceLayout(constants: { force_floats: number }): void {
  if (constants.force_floats !== FORCE_FLOATS) {
    throw new Error(`the physics engine does not match the page: it writes ${constants.force_floats} floats per body's forces, the page reads ${FORCE_FLOATS}; rebuild both`);
  }
}

/** The kinds of force in a row, in the row's order. */
export const FORCE_KINDS = ["weight", "buoyancy", "drag", "contact", "ribbon", "other"] as const;
export type ForceKind = (typeof FORCE_KINDS)[number];

export type Vec3 = [number, number, number];

/** One body's forces over the last step, world frame. */
export interface ForceRow {
  /** Dense body index in the frame's order. */
  index: number;
  /** N, by kind. */
  forces: Record<ForceKind, Vec3>;
  centerOfMass: Vec3;
  centerOfBuoyancy: Vec3;
  /** Where the ribbon is tied; null without a ribbon. */
  knot: Vec3 | null;
}

const vec = (a: ArrayLike<number>, o: number): Vec3 => [a[o], a[o + 1], a[o + 2]];

/** Row `i` of `rows` (`FORCE_FLOATS` floats each). */
export function readForceRow(rows: ArrayLike<number>, i: number): ForceRow {
  const o = i * FORCE_FLOATS;
  const forces = {} as Record<ForceKind, Vec3>;
  FORCE_KINDS.forEach((kind, k) => (forces[kind] = vec(rows, o + 1 + 3 * k)));
  const knot = vec(rows, o + 25);
  return {
    index: rows[o],
    forces,
    centerOfMass: vec(rows, o + 19),
    centerOfBuoyancy: vec(rows, o + 22),
    knot: knot.some((v) => Number.isNaN(v)) ? null : knot,
  };
}

/** How many rows `rows` holds. */
export function forceRowCount(rows: ArrayLike<number>): number {
  return Math.floor(rows.length / FORCE_FLOATS);
}

/** The row of body `index`, or null when the rows have none. */
export function findForceRow(rows: ArrayLike<number>, index: number): ForceRow | null {
  const n = forceRowCount(rows);
  for (let i = 0; i < n; i++) if (rows[i * FORCE_FLOATS] === index) return readForceRow(rows, i);
  return null;
}

/** The sum of a row's forces, N. */
export function netForce(row: ForceRow): Vec3 {
  const sum: Vec3 = [0, 0, 0];
  for (const kind of FORCE_KINDS) for (let a = 0; a < 3; a++) sum[a] += row.forces[kind][a];
  return sum;
}

/** What a frame carries of the forces while a balloon is selected or every balloon's are shown. */
export interface ForcesPayload {
  /** `FORCE_FLOATS` per probed body (the selected one, or all). */
  rows: Float32Array<ArrayBuffer>;
  /** The selected body's dense index in this frame's order; -1 when none. */
  selected: number;
  /** The engine's card of the selected body; null when none. */
  card: BodyCard | null;
}

/** The part of the engine probing needs (the worker's `Engine`). */
export interface ForceSource {
  setForceProbe(which: number): void;
  forces(): Float32Array;
  bodyCard(index: number): BodyCard;
  bodyCount(): number;
}

/** `set_force_probe`'s arguments besides a body index. */
export const PROBE_OFF = -1;
export const PROBE_ALL = -2;

/**
 * The worker's record of what is probed. The selection is a dense index,
 * kept in step as bodies are removed (the engine moves the last body into a
 * removed one's place); while one body is probed the engine follows it by its
 * own handle and each row says where it is now.
 */
export class ForceProbe {
  /** The selected body's dense index now; -1 when none. */
  selected = -1;
  /** Every body's forces (the panel's "forces on all"). */
  all = false;
  /** What the engine was last told (null: nothing yet in this world). */
  private applied: number | null = null;
  /** Whether a step has run since the engine was last told. */
  private steppedSinceApply = false;

  /** What `set_force_probe` should be given now. */
  get which(): number {
    return this.all ? PROBE_ALL : this.selected >= 0 ? this.selected : PROBE_OFF;
  }

  /** Whether frames carry forces. */
  get active(): boolean {
    return this.which !== PROBE_OFF;
  }

  select(index: number): void {
    this.selected = index;
  }

  setAll(on: boolean): void {
    this.all = on;
  }

  /** A new world: nothing selected, and the engine knows nothing of the probe. */
  worldRebuilt(): void {
    this.selected = -1;
    this.applied = null;
  }

  /** Body `index` of `countBefore` was removed; the last one took its place. */
  removed(index: number, countBefore: number): void {
    const before = this.selected;
    if (this.selected === index) this.selected = -1;
    else if (this.selected === countBefore - 1) this.selected = index;
    // The engine follows a probed body by its own handle: the same body under a new index needs no telling.
    if (!this.all && this.selected >= 0 && this.applied === before) this.applied = this.selected;
  }

  /** Tells the engine what to record from the next step on, when that changed. */
  apply(engine: ForceSource): void {
    const which = this.which;
    if (which === this.applied) return;
    engine.setForceProbe(which);
    this.applied = which;
    this.steppedSinceApply = false;
  }

  /** A step ran. */
  stepped(): void {
    this.steppedSinceApply = true;
  }

  /** The payload of the next frame (copies), or null when nothing is probed. */
  collect(engine: ForceSource): ForcesPayload | null {
    if (!this.active) return null;
    const rows = engine.forces().slice();
    if (!this.all && this.selected >= 0) {
      if (rows.length >= FORCE_FLOATS) {
        // The engine followed the body by its handle: this is where it is now.
        this.selected = rows[0];
        this.applied = this.selected;
      } else if (this.steppedSinceApply) {
        // Stepped and nothing recorded: the body left the world (removed by the engine itself).
        this.selected = -1;
      }
    }
    const count = engine.bodyCount();
    if (this.selected >= count) this.selected = -1;
    const card = this.selected >= 0 ? engine.bodyCard(this.selected) : null;
    return { rows, selected: this.selected, card };
  }
}
