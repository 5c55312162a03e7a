// A lighter balloon for crowds. The balloon OBJ is a surface of revolution
// (rings of vertices around the Y axis, 2,736 triangles); thousands of them
// cost millions of triangles per pass. Above CROWD_BALLOONS the balloons are
// drawn with a lathe of the same profile: fewer rings and segments, the same
// silhouette to within a few millimetres.

/** Balloons above which the crowd geometry is used. */
export const CROWD_BALLOONS = 500;

/**
 * The profile of a surface of revolution about Y: one (radius, y) point per
 * ring of vertices (vertices within `tolerance` m in y form a ring), bottom
 * to top, radius the mean distance from the axis.
 */
export function revolutionProfile(positions: ArrayLike<number>, tolerance = 1e-5): [number, number][] {
  const points: { y: number; r: number }[] = [];
  for (let i = 0; i + 2 < positions.length; i += 3) {
    points.push({ y: positions[i + 1], r: Math.hypot(positions[i], positions[i + 2]) });
  }
  points.sort((a, b) => a.y - b.y);
  const rings: [number, number][] = [];
  let sumR = 0;
  let sumY = 0;
  let n = 0;
  const flush = () => {
    if (n > 0) rings.push([sumR / n, sumY / n]);
    sumR = 0;
    sumY = 0;
    n = 0;
  };
  for (const p of points) {
    if (n > 0 && p.y - sumY / n > tolerance) flush();
    sumR += p.r;
    sumY += p.y;
    n++;
  }
  flush();
  return rings;
}

/**
 * Keeps every `step`-th ring of `profile`, and always the first and last
 * (the poles), so the height and the knot stay where they are.
 */
export function thinProfile(profile: [number, number][], step: number): [number, number][] {
  if (profile.length <= 2 || step <= 1) return profile.slice();
  const kept = profile.filter((_, i) => i % step === 0);
  if (kept[kept.length - 1] !== profile[profile.length - 1]) kept.push(profile[profile.length - 1]);
  return kept;
}
