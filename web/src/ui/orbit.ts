// Spherical camera orbit around a fixed centre at a constant distance: the
// arrow-key navigation of the original UP (report, section 3.3). Pure maths,
// no three.js, so it is unit-tested on its own.

export interface Vec3Like {
  x: number;
  y: number;
  z: number;
}

/** Azimuth and elevation in radians; distance in metres. */
export interface OrbitAngles {
  /** Around +Y, 0 looks from +Z towards the centre; rad. */
  azimuth: number;
  /** Above the horizontal plane through the centre; rad, clamped to ±ELEVATION_LIMIT. */
  elevation: number;
  /** Metres from the centre; never changed by the arrow keys. */
  distance: number;
}

/** Just short of the poles, so "up" stays well defined (rad, ≈ 84°). */
export const ELEVATION_LIMIT = (84 * Math.PI) / 180;

/** Arrow-key turn rate, rad/s (a full turn in about 7 s). */
export const ORBIT_RATE = 0.9;

export function clampElevation(elevation: number): number {
  return Math.min(ELEVATION_LIMIT, Math.max(-ELEVATION_LIMIT, elevation));
}

/** Wraps an angle into (−π, π]. */
export function wrapAngle(angle: number): number {
  const twoPi = 2 * Math.PI;
  let a = angle % twoPi;
  if (a <= -Math.PI) a += twoPi;
  if (a > Math.PI) a -= twoPi;
  return a;
}

/** Spherical to Cartesian: the camera position for `angles` around `center`. */
export function orbitPosition(center: Vec3Like, angles: OrbitAngles): Vec3Like {
  const horizontal = angles.distance * Math.cos(angles.elevation);
  return {
    x: center.x + horizontal * Math.sin(angles.azimuth),
    y: center.y + angles.distance * Math.sin(angles.elevation),
    z: center.z + horizontal * Math.cos(angles.azimuth),
  };
}

/** Cartesian to spherical: the inverse of `orbitPosition` (elevation clamped). */
export function orbitAngles(center: Vec3Like, position: Vec3Like): OrbitAngles {
  const dx = position.x - center.x;
  const dy = position.y - center.y;
  const dz = position.z - center.z;
  const distance = Math.hypot(dx, dy, dz);
  if (distance === 0) return { azimuth: 0, elevation: 0, distance: 0 };
  return {
    azimuth: Math.atan2(dx, dz),
    elevation: clampElevation(Math.asin(Math.max(-1, Math.min(1, dy / distance)))),
    distance,
  };
}

/** Which arrow keys are held. */
export interface ArrowState {
  left: boolean;
  right: boolean;
  up: boolean;
  down: boolean;
}

/**
 * Advances the orbit by `dt` seconds of held arrow keys: left/right turn the
 * azimuth, up/down the elevation (clamped); the distance never changes.
 */
export function stepOrbit(angles: OrbitAngles, keys: ArrowState, dt: number, rate = ORBIT_RATE): OrbitAngles {
  const turn = (Number(keys.right) - Number(keys.left)) * rate * dt;
  const tilt = (Number(keys.up) - Number(keys.down)) * rate * dt;
  return {
    azimuth: wrapAngle(angles.azimuth + turn),
    elevation: clampElevation(angles.elevation + tilt),
    distance: angles.distance,
  };
}

export function anyArrowHeld(keys: ArrowState): boolean {
  return keys.left || keys.right || keys.up || keys.down;
}

/**
 * How much farther the home view stands back in a window of `aspect` (width
 * over height): 1 for a landscape window, growing as the window narrows (the
 * field of view is vertical, so the room's width is what a portrait cuts).
 */
export function portraitPullBack(aspect: number): number {
  return aspect >= 1 ? 1 : Math.pow(1 / Math.max(0.3, aspect), 0.75);
}
