// Which balloons the foil meshes draw: pure bookkeeping over the frame's
// model indices and poses, kept apart from three.js so it can be tested.

import { POSE_STRIDE } from "./poseMath";

/**
 * Per balloon model, the dense indices of its bodies in dense order when the
 * model is foil (`isFoil[model]`), else an empty list: latex bodies are the
 * latex mesh's, which draws every body in place.
 */
export function bodiesByFoilModel(models: Uint32Array, isFoil: readonly boolean[]): Uint32Array[] {
  const counts = isFoil.map(() => 0);
  for (let i = 0; i < models.length; i++) if (isFoil[models[i]]) counts[models[i]]++;
  const lists = counts.map((n) => new Uint32Array(n));
  counts.fill(0);
  for (let i = 0; i < models.length; i++) {
    const m = models[i];
    if (isFoil[m]) lists[m][counts[m]++] = i;
  }
  return lists;
}

/**
 * Copies the poses (and sizes) of `bodies` into the first `bodies.length`
 * slots of `poses` (and `scales`), so the instance writer reads them in a
 * row; a body past the end of `from` (a frame shorter than its tables) gets
 * the identity pose, a size past `fromScales` 1. Returns how many bodies.
 */
export function gatherPoses(
  from: Float32Array,
  fromScales: Float32Array,
  bodies: Uint32Array,
  poses: Float32Array,
  scales: Float32Array,
): number {
  for (let k = 0; k < bodies.length; k++) {
    const b = bodies[k];
    const src = b * POSE_STRIDE;
    const dst = k * POSE_STRIDE;
    if (src + POSE_STRIDE <= from.length) {
      for (let j = 0; j < POSE_STRIDE; j++) poses[dst + j] = from[src + j];
    } else {
      poses.fill(0, dst, dst + POSE_STRIDE);
      poses[dst + 6] = 1;
    }
    scales[k] = b < fromScales.length ? fromScales[b] : 1;
  }
  return bodies.length;
}
