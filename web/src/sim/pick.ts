// Picking a balloon under the pointer: a ray against each balloon's root
// sphere, then against the leaves of those it passes through (the same sphere
// tree the engine collides with). Pure maths over the pose array.

import { POSE_STRIDE, transformPoint } from "./poseLayout";

export interface Ray {
  origin: [number, number, number];
  /** Unit length. */
  direction: [number, number, number];
}

/** A sphere in a balloon's body frame. */
export interface BodySphere {
  center: [number, number, number];
  radius: number;
}

export interface Hit {
  /** Dense body index. */
  index: number;
  /** Distance along the ray, m. */
  distance: number;
  point: [number, number, number];
}

/** Distance along `ray` to the sphere's surface, or `Infinity` when missed (0 when inside). */
export function raySphere(ray: Ray, cx: number, cy: number, cz: number, r: number): number {
  const ox = ray.origin[0] - cx;
  const oy = ray.origin[1] - cy;
  const oz = ray.origin[2] - cz;
  const [dx, dy, dz] = ray.direction;
  const b = ox * dx + oy * dy + oz * dz;
  const c = ox * ox + oy * oy + oz * oz - r * r;
  if (c <= 0) return 0;
  if (b > 0) return Infinity;
  const disc = b * b - c;
  if (disc < 0) return Infinity;
  return -b - Math.sqrt(disc);
}

/**
 * The nearest balloon hit by `ray`, or `null`. `roots[m]` and `leaves[m]` are
 * model m's root and leaf spheres; `models[i]` is body i's model (0 when null);
 * `scales[i]` is body i's size over its model's (1 when null or short: a
 * balloon that has lost gas is smaller, about its mesh frame's origin).
 */
export function pickBalloon(
  ray: Ray,
  poses: Float32Array,
  count: number,
  roots: BodySphere[],
  leaves: BodySphere[][],
  models: Uint32Array | null,
  scales: Float32Array | null = null,
): Hit | null {
  let best: Hit | null = null;
  const c = [0, 0, 0];
  for (let i = 0; i < count; i++) {
    const m = models ? models[i] : 0;
    const root = roots[m];
    if (!root) continue;
    const s = scales && i < scales.length ? scales[i] : 1;
    const o = i * POSE_STRIDE;
    transformPoint(poses, o, root.center[0] * s, root.center[1] * s, root.center[2] * s, c);
    const tRoot = raySphere(ray, c[0], c[1], c[2], root.radius * s);
    if (tRoot === Infinity || (best && tRoot > best.distance)) continue;
    for (const leaf of leaves[m] ?? [root]) {
      transformPoint(poses, o, leaf.center[0] * s, leaf.center[1] * s, leaf.center[2] * s, c);
      const t = raySphere(ray, c[0], c[1], c[2], leaf.radius * s);
      if (t < (best ? best.distance : Infinity)) {
        best = {
          index: i,
          distance: t,
          point: [ray.origin[0] + ray.direction[0] * t, ray.origin[1] + ray.direction[1] * t, ray.origin[2] + ray.direction[2] * t],
        };
      }
    }
  }
  return best;
}

/** Where `ray` meets the horizontal plane y = `height`, or `null` when parallel or behind. */
export function rayHorizontalPlane(ray: Ray, height: number): [number, number, number] | null {
  const dy = ray.direction[1];
  if (Math.abs(dy) < 1e-9) return null;
  const t = (height - ray.origin[1]) / dy;
  if (t < 0) return null;
  return [ray.origin[0] + ray.direction[0] * t, height, ray.origin[2] + ray.direction[2] * t];
}

/** A ribbon's free end near the pointer's ray. */
export interface RibbonEndHit {
  /** Ribbon index (the frame's ribbon order). */
  ribbon: number;
  /** The end's point index within its ribbon (its point count less one). */
  point: number;
  /** Distance along the ray to the end's nearest approach, m. */
  distance: number;
  /** The end, world frame, m. */
  position: [number, number, number];
}

/**
 * The ribbon free end nearest the ray (by angle) among those within
 * `radiansPerPixel × pixels` of it as seen from the ray's origin, or `null`.
 * `points` are all ribbons' points (x, y, z each); `offsets` each ribbon's
 * first point, then the total.
 */
export function pickRibbonEnd(ray: Ray, points: Float32Array, offsets: Uint32Array, radiansPerPixel: number, pixels: number): RibbonEndHit | null {
  const [ox, oy, oz] = ray.origin;
  const [dx, dy, dz] = ray.direction;
  const reach = radiansPerPixel * pixels;
  let best: RibbonEndHit | null = null;
  let bestAngle = Infinity;
  for (let r = 0; r + 1 < offsets.length; r++) {
    const count = offsets[r + 1] - offsets[r];
    if (count < 2) continue;
    const e = (offsets[r + 1] - 1) * 3;
    if (e + 2 >= points.length) break;
    const x = points[e] - ox;
    const y = points[e + 1] - oy;
    const z = points[e + 2] - oz;
    const t = x * dx + y * dy + z * dz;
    if (t <= 0) continue;
    const off = Math.hypot(x - t * dx, y - t * dy, z - t * dz);
    const angle = off / t;
    if (angle <= reach && angle < bestAngle) {
      bestAngle = angle;
      best = { ribbon: r, point: count - 1, distance: t, position: [points[e], points[e + 1], points[e + 2]] };
    }
  }
  return best;
}
