// Where the parts of a drawn fan or vent go, as pure maths: a fan is a base
// on the floor, a pole up to a pivot behind the outlet, a motor behind the
// blades, the blades in the outlet's plane and a guard ring round them, the
// head turned to where the fan blows now (so a sweeping fan's head swings);
// a vent is a square diffuser in the plane of its outlet. And how fast the
// drawn blades turn.

import type { Vec3 } from "../sim/airLayout";

/** Fastest the drawn blades turn, revolutions per second: three blades passing 9 times a second still read as turning at 60 frames a second. */
export const MAX_DRAWN_REV_S = 3;
/** The motor's centre behind the outlet, in diameters. */
export const MOTOR_BEHIND_D = 0.3;
/** An outlet lower than this over the floor is a floor fan: no pole, m. */
export const MIN_POLE_M = 0.05;

/**
 * The drawn blades' turn rate, rad/s: as if their tips moved at the
 * outlet's air speed (a real fan's turn several times faster, which a
 * picture at 60 Hz shows as a flicker), at most `MAX_DRAWN_REV_S`.
 */
export function bladeTurnRate(speed: number, diameter: number): number {
  if (!(speed > 0) || !(diameter > 0)) return 0;
  const revPerS = Math.min(MAX_DRAWN_REV_S, speed / (Math.PI * diameter));
  return 2 * Math.PI * revPerS;
}

/** The unit quaternion (x, y, z, w) turning +z onto unit `aim`. */
export function quaternionFromZ(aim: Vec3): [number, number, number, number] {
  const [x, y, z] = aim;
  const d = z;
  if (d < -0.999999) return [0, 1, 0, 0]; // half a turn about y
  // q = (z × aim, 1 + z·aim), normalised.
  const qx = -y;
  const qy = x;
  const qw = 1 + d;
  const n = Math.hypot(qx, qy, qw);
  return [qx / n, qy / n, 0, qw / n];
}

export interface FanPose {
  /** The head (motor, blades, guard), turned from +z onto the aim. */
  head: { outlet: Vec3; motor: Vec3; rotation: [number, number, number, number] };
  /** The pole: from the floor under the motor up to it, m (length 0: a floor fan). */
  pole: { bottom: Vec3; length: number };
  /** The base's centre on the floor. */
  base: Vec3;
}

/** Where the parts of a fan blowing from `outlet` along unit `aim` go, its base on the floor at `floorY`. */
export function fanPose(outlet: Vec3, aim: Vec3, diameter: number, floorY: number): FanPose {
  const behind = MOTOR_BEHIND_D * diameter;
  const motor: Vec3 = [outlet[0] - aim[0] * behind, outlet[1] - aim[1] * behind, outlet[2] - aim[2] * behind];
  const height = motor[1] - floorY;
  return {
    head: { outlet: [...outlet], motor, rotation: quaternionFromZ(aim) },
    pole: { bottom: [motor[0], floorY, motor[2]], length: height > MIN_POLE_M ? height : 0 },
    base: [motor[0], floorY, motor[2]],
  };
}

/** Rotates `v` by unit quaternion `q` (x, y, z, w). */
export function rotate(q: [number, number, number, number], v: Vec3): Vec3 {
  const [qx, qy, qz, qw] = q;
  const tx = 2 * (qy * v[2] - qz * v[1]);
  const ty = 2 * (qz * v[0] - qx * v[2]);
  const tz = 2 * (qx * v[1] - qy * v[0]);
  return [v[0] + qw * tx + (qy * tz - qz * ty), v[1] + qw * ty + (qz * tx - qx * tz), v[2] + qw * tz + (qx * ty - qy * tx)];
}
