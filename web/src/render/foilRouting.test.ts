import { describe, expect, it } from "vitest";
import { bodiesByFoilModel, gatherPoses } from "./foilRouting";
import { POSE_STRIDE, writeInstanceMatrices } from "./poseMath";

describe("foil routing", () => {
  it("lists each foil model's bodies in dense order and none of a latex model's", () => {
    const models = Uint32Array.from([0, 2, 1, 2, 0, 1, 2]);
    const lists = bodiesByFoilModel(models, [false, true, true]);
    expect(lists.map((l) => Array.from(l))).toEqual([[], [2, 5], [1, 3, 6]]);
    expect(bodiesByFoilModel(models, [false, false, false]).every((l) => l.length === 0)).toBe(true);
    expect(bodiesByFoilModel(new Uint32Array(0), [true]).map((l) => l.length)).toEqual([0]);
  });

  it("a model index past the table is latex, not a crash", () => {
    expect(bodiesByFoilModel(Uint32Array.from([0, 5]), [true]).map((l) => Array.from(l))).toEqual([[0]]);
  });

  it("gathers the chosen bodies' poses and sizes in a row", () => {
    const n = 4;
    const from = new Float32Array(n * POSE_STRIDE).map((_, i) => i);
    const sizes = Float32Array.from([1, 0.9, 0.8, 0.7]);
    const poses = new Float32Array(3 * POSE_STRIDE).fill(-1);
    const scales = new Float32Array(3).fill(-1);
    expect(gatherPoses(from, sizes, Uint32Array.from([3, 1]), poses, scales)).toBe(2);
    expect(Array.from(poses.subarray(0, POSE_STRIDE))).toEqual(Array.from(from.subarray(3 * POSE_STRIDE, 4 * POSE_STRIDE)));
    expect(Array.from(poses.subarray(POSE_STRIDE, 2 * POSE_STRIDE))).toEqual(Array.from(from.subarray(POSE_STRIDE, 2 * POSE_STRIDE)));
    expect(Array.from(scales.subarray(0, 2))).toEqual([Math.fround(0.7), Math.fround(0.9)]);
    expect(poses[2 * POSE_STRIDE]).toBe(-1);
  });

  it("a body the frame lacks gets the identity pose and size 1", () => {
    const poses = new Float32Array(POSE_STRIDE).fill(5);
    const scales = new Float32Array(1);
    gatherPoses(new Float32Array(POSE_STRIDE), new Float32Array(0), Uint32Array.from([1]), poses, scales);
    expect(Array.from(poses)).toEqual([0, 0, 0, 0, 0, 0, 1]);
    expect(scales[0]).toBe(1);
  });

  it("matrices written from gathered poses are those of the bodies in place", () => {
    const n = 3;
    const prev = new Float32Array(n * POSE_STRIDE);
    const curr = new Float32Array(n * POSE_STRIDE);
    for (let i = 0; i < n; i++) {
      const q = [Math.sin(0.3 * i), 0, 0, Math.cos(0.3 * i)];
      prev.set([i, 1 + i, -i, ...q], i * POSE_STRIDE);
      curr.set([i + 0.5, 2 + i, -i, ...q], i * POSE_STRIDE);
    }
    const sizes = Float32Array.from([1, 0.5, 0.8]);
    const whole = new Float32Array(n * 16);
    writeInstanceMatrices(whole, prev, curr, n, 0.25, sizes);
    const bodies = Uint32Array.from([2, 0]);
    const gp = new Float32Array(2 * POSE_STRIDE);
    const gc = new Float32Array(2 * POSE_STRIDE);
    const gs = new Float32Array(2);
    gatherPoses(prev, sizes, bodies, gp, gs);
    gatherPoses(curr, sizes, bodies, gc, gs);
    const some = new Float32Array(2 * 16);
    writeInstanceMatrices(some, gp, gc, 2, 0.25, gs);
    expect(Array.from(some.subarray(0, 16))).toEqual(Array.from(whole.subarray(32, 48)));
    expect(Array.from(some.subarray(16, 32))).toEqual(Array.from(whole.subarray(0, 16)));
  });
});
