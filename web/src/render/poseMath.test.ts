import { describe, expect, it } from "vitest";
import { Matrix4, Quaternion, Vector3 } from "three";
import { composeMatrix, transformPoint, writeInstanceMatrices } from "./poseMath";

describe("pose to instance matrix", () => {
  it("matches three's Matrix4.compose", () => {
    const q = new Quaternion().setFromAxisAngle(new Vector3(1, 2, 3).normalize(), 0.8);
    const out = new Float32Array(16);
    composeMatrix(out, 0, 1, 2, 3, q.x, q.y, q.z, q.w, 1.5);
    const m = new Matrix4().compose(new Vector3(1, 2, 3), q, new Vector3(1.5, 1.5, 1.5));
    m.elements.forEach((e, i) => expect(out[i]).toBeCloseTo(e, 5));
  });

  it("interpolates position linearly and rotation on the short arc", () => {
    const prev = new Float32Array([0, 0, 0, 0, 0, 0, 1]);
    const s = Math.sin(0.5);
    // The same rotation written as −q: the blend must not pass through zero.
    const curr = new Float32Array([2, 4, 6, -s, 0, 0, -Math.cos(0.5)]);
    const out = new Float32Array(16);
    writeInstanceMatrices(out, prev, curr, 1, 0.5);
    expect([out[12], out[13], out[14]]).toEqual([1, 2, 3]);
    const q = new Quaternion().setFromRotationMatrix(new Matrix4().fromArray(Array.from(out)));
    expect(2 * Math.acos(Math.min(1, Math.abs(q.w)))).toBeCloseTo(0.5, 4);
  });

  it("clamps alpha and applies per-body scale", () => {
    const pose = new Float32Array([1, 1, 1, 0, 0, 0, 1, 5, 5, 5, 0, 0, 0, 1]);
    const out = new Float32Array(32);
    writeInstanceMatrices(out, pose, pose, 2, 7, new Float32Array([2, 3]));
    expect(out[0]).toBe(2);
    expect(out[16]).toBe(3);
    expect(out[28]).toBe(5);
  });

  it("transforms a body-frame point to the world", () => {
    const q = new Quaternion().setFromAxisAngle(new Vector3(0, 0, 1), Math.PI / 2);
    const pose = new Float32Array([10, 0, 0, q.x, q.y, q.z, q.w]);
    const out = [0, 0, 0];
    transformPoint(pose, 0, 1, 0, 0, out);
    expect(out[0]).toBeCloseTo(10, 5);
    expect(out[1]).toBeCloseTo(1, 5);
    expect(out[2]).toBeCloseTo(0, 5);
  });
});
