// The fan tool's decisions, as pure functions over floor points: where a
// click puts a fan and where a drag aims it, which fan a click near one
// picks instead, and the fan the engine is asked to add.

import type { AirSource, Vec3 } from "../sim/airLayout";
import type { FanDef } from "../sim/engine";

/** A placed fan's outlet over the floor, m: a pedestal fan's head. */
export const FAN_OUTLET_HEIGHT_M = 1.0;
/** A placed fan's outlet diameter, m (a 16-inch household fan). */
export const FAN_DIAMETER_M = 0.4;
/** A placed fan's outlet speed until the panel says otherwise, m/s (a household fan's middle setting). */
export const FAN_SPEED_M_S = 3;
/** A sweeping fan's total swing, degrees, and one swing there and back, s (an oscillating household fan's). */
export const FAN_SWEEP_DEG = 90;
export const FAN_SWEEP_PERIOD_S = 12;
/** A drag shorter than this on the floor is a click: the fan faces the room's centre, m. */
export const MIN_AIM_DRAG_M = 0.15;
/** A click this near a fan's stand (on the floor, m) picks that fan instead of placing one. */
export const FAN_PICK_RADIUS_M = 0.35;

/** Where a drag from floor point `start` to `end` (x, z each, m) aims a fan: level, from start toward end; null for a click. */
export function fanAimFromDrag(start: [number, number], end: [number, number], minDrag = MIN_AIM_DRAG_M): Vec3 | null {
  const dx = end[0] - start[0];
  const dz = end[1] - start[1];
  const length = Math.hypot(dx, dz);
  if (!(length >= minDrag)) return null;
  return [dx / length, 0, dz / length];
}

/** A clicked fan's aim: level, toward the room's centre `center` (x, z), or along +z from the centre itself. */
export function defaultFanAim(start: [number, number], center: [number, number] = [0, 0]): Vec3 {
  return fanAimFromDrag(start, center, 1e-3) ?? [0, 0, 1];
}

/** The fan the engine is asked to add at floor point `at` (x, z), blowing along `aim`. */
export function fanAt(at: [number, number], floorY: number, aim: Vec3, speed: number, sweeps: boolean): FanDef {
  return {
    position: [at[0], floorY + FAN_OUTLET_HEIGHT_M, at[1]],
    direction: [...aim],
    diameter_m: FAN_DIAMETER_M,
    speed_m_s: speed,
    sweep_deg: sweeps ? FAN_SWEEP_DEG : 0,
    sweep_period_s: FAN_SWEEP_PERIOD_S,
  };
}

/** The jet index of the fan whose stand is nearest floor point `at` (x, z) within `radius`, or -1. */
export function fanNear(at: [number, number], sources: readonly AirSource[], radius = FAN_PICK_RADIUS_M): number {
  let best = -1;
  let bestDistance = radius;
  for (const s of sources) {
    if (s.kind !== "fan") continue;
    const d = Math.hypot(s.outlet[0] - at[0], s.outlet[2] - at[1]);
    if (d <= bestDistance) {
      best = s.jet;
      bestDistance = d;
    }
  }
  return best;
}
