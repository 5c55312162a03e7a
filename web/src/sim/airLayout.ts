// The moving air as the engine writes it for the page (crates/up-wasm/src/air.rs):
// one row of floats per source (fans and vents, then draughts), and the
// field sampled on a coarse grid of the room. Pure reading of those arrays,
// and the grid's size for a room.

import type { AirGridStride, AirSourceStride } from "../../public/wasm/up_wasm";
import type { Constants } from "./engine";

/**
 * Floats per source row (`constants().air.source_stride`): kind, outlet x y z
 * (m), aim now x y z (unit), speed now (m/s, its schedule applied), full
 * speed (m/s), diameter (m), total sweep (rad), sweep period (s).
 */
export const AIR_SOURCE_STRIDE: AirSourceStride = 12;
/** Floats per grid cell (`constants().air.grid_stride`): ux, uy, uz (m/s), |u|. */
export const AIR_GRID_STRIDE: AirGridStride = 4;

/** A row's `kind`, as the engine numbers them. */
export const SOURCE_KINDS = ["fan", "vent", "draught"] as const;
export type SourceKind = (typeof SOURCE_KINDS)[number];

export type Vec3 = [number, number, number];

/** One source of moving air, now. */
export interface AirSource {
  kind: SourceKind;
  /** Index among the world's jets (fans and vents), the name the air commands use; -1 for a draught. */
  jet: number;
  outlet: Vec3;
  /** Where it blows now (a sweeping fan turns), unit. */
  aim: Vec3;
  /** Outlet speed now and at full power, m/s. */
  speed: number;
  fullSpeed: number;
  /** Outlet diameter, m. */
  diameter: number;
  /** Total swing about the vertical, rad (0: still). */
  sweep: number;
}

/** Throws unless the engine writes the air with the strides the page reads. */
export function checkAirLayout(constants: Pick<Constants, "air">): void {
  const { source_stride, grid_stride } = constants.air;
  if (source_stride !== AIR_SOURCE_STRIDE || grid_stride !== AIR_GRID_STRIDE) {
    throw new Error(
      `the physics engine does not match the page: it writes ${source_stride} floats per air source and ${grid_stride} per air cell, the page reads ${AIR_SOURCE_STRIDE} and ${AIR_GRID_STRIDE}; rebuild both`,
    );
  }
}

/** The sources of `rows` (`AIR_SOURCE_STRIDE` floats each), in the engine's order. */
export function readSources(rows: ArrayLike<number>): AirSource[] {
  const out: AirSource[] = [];
  let jet = 0;
  for (let o = 0; o + AIR_SOURCE_STRIDE <= rows.length; o += AIR_SOURCE_STRIDE) {
    const kind = SOURCE_KINDS[rows[o]] ?? "fan";
    out.push({
      kind,
      jet: kind === "draught" ? -1 : jet++,
      outlet: [rows[o + 1], rows[o + 2], rows[o + 3]],
      aim: [rows[o + 4], rows[o + 5], rows[o + 6]],
      speed: rows[o + 7],
      fullSpeed: rows[o + 8],
      diameter: rows[o + 9],
      sweep: rows[o + 10],
    });
  }
  return out;
}

/** The field on a grid of the room, as `Engine.write_air_grid` samples it. */
export interface AirField {
  /** Cells along x, y, z; x runs fastest in `cells`, then y, then z. */
  dims: Vec3;
  /** The box the cells tile, m: cell (i, j, k)'s centre is min + ((i, j, k) + ½)·(max − min)/dims. */
  min: Vec3;
  max: Vec3;
  /** `AIR_GRID_STRIDE` floats a cell. */
  cells: Float32Array;
  /** Simulated time of the sample, s. */
  time: number;
  /** Whether the room has any source (without one every cell is zero). */
  moving: boolean;
}

/** A cell's edge the page samples the air on, m: a jet from a 40 cm fan spans a few. */
export const AIR_CELL_M = 0.25;
/** Most cells along an axis the page asks for (a big room's cells grow instead). */
export const AIR_MAX_CELLS_PER_AXIS = 32;

/** Cells along each axis for a box of `size` (m): about `cell` m each, at least 2 and at most `maxPerAxis`. */
export function airGridDims(size: Vec3, cell = AIR_CELL_M, maxPerAxis = AIR_MAX_CELLS_PER_AXIS): Vec3 {
  const axis = (s: number) => Math.min(maxPerAxis, Math.max(2, Math.round(s / cell)));
  return [axis(size[0]), axis(size[1]), axis(size[2])];
}
