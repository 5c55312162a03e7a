// The worker's side of the moving air: the sources' rows that ride in each
// frame while the room has any, and the field sampled on a coarse grid of
// the room every `AIR_FIELD_INTERVAL_MS` while "show air" is on (the page's
// motes are carried by it: render/airMotes.ts). The engine samples; this
// only paces the samples and copies them out of wasm memory.

import type { Engine } from "./engine";
import { airGridDims, type AirField, type Vec3 } from "./airLayout";

/** How often the field is sampled while shown, ms: a sweeping fan turns a few degrees in between. */
export const AIR_FIELD_INTERVAL_MS = 250;

/** The box around the room's vertices (x, y, z each), m. */
export function roomBox(vertices: ArrayLike<number>): { min: Vec3; max: Vec3 } {
  const min: Vec3 = [Infinity, Infinity, Infinity];
  const max: Vec3 = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i + 2 < vertices.length; i += 3) {
    for (let a = 0; a < 3; a++) {
      min[a] = Math.min(min[a], vertices[i + a]);
      max[a] = Math.max(max[a], vertices[i + a]);
    }
  }
  return { min, max };
}

export class AirSampler {
  /** Whether the page shows the air (and wants the field). */
  show = false;
  /** Cells along x, y, z for the current room. */
  private dims: Vec3 = [2, 2, 2];
  private lastSample = -Infinity;
  /** Whether the last field sent had moving air: a room that went still gets one still field, then none. */
  private lastMoving = false;

  /** A new world: the grid fits its room, and the next tick samples at once. */
  worldRebuilt(roomVertices: ArrayLike<number>): void {
    const { min, max } = roomBox(roomVertices);
    this.dims = airGridDims([max[0] - min[0], max[1] - min[1], max[2] - min[2]]);
    this.lastSample = -Infinity;
    this.lastMoving = true;
  }

  setShow(on: boolean): void {
    this.show = on;
    this.lastSample = -Infinity;
    this.lastMoving = true;
  }

  /** The sources changed (a fan placed or removed): the next tick samples at once. */
  changed(): void {
    this.lastSample = -Infinity;
    this.lastMoving = true;
  }

  /** The sources' rows for a frame (a copy), or undefined when the room has none. */
  sources(engine: Engine): Float32Array | undefined {
    const rows = engine.airSources();
    return rows.length > 0 ? rows.slice() : undefined;
  }

  /** The field when one is due (`nowMs`, the worker's clock), else null. */
  sample(engine: Engine, nowMs: number): AirField | null {
    if (!this.show || nowMs - this.lastSample < AIR_FIELD_INTERVAL_MS) return null;
    this.lastSample = nowMs;
    const [nx, ny, nz] = this.dims;
    const { grid, cells } = engine.airGrid(nx, ny, nz);
    if (!grid.moving && !this.lastMoving) return null;
    this.lastMoving = grid.moving;
    return {
      dims: [grid.dims[0], grid.dims[1], grid.dims[2]],
      min: [grid.min[0], grid.min[1], grid.min[2]],
      max: [grid.max[0], grid.max[1], grid.max[2]],
      cells: cells.slice(),
      time: grid.time_s,
      moving: grid.moving,
    };
  }
}
