import { describe, expect, it } from "vitest";
import { pickBalloon, pickRibbonEnd, rayHorizontalPlane, raySphere } from "./pick";

const ray = (origin: [number, number, number], direction: [number, number, number]) => {
  const l = Math.hypot(...direction);
  return { origin, direction: direction.map((d) => d / l) as [number, number, number] };
};

describe("picking", () => {
  it("intersects a ray with a sphere", () => {
    expect(raySphere(ray([0, 0, -5], [0, 0, 1]), 0, 0, 0, 1)).toBeCloseTo(4, 6);
    expect(raySphere(ray([0, 2, -5], [0, 0, 1]), 0, 0, 0, 1)).toBe(Infinity);
    expect(raySphere(ray([0, 0, 5], [0, 0, 1]), 0, 0, 0, 1)).toBe(Infinity);
    expect(raySphere(ray([0, 0, 0.5], [0, 0, 1]), 0, 0, 0, 1)).toBe(0);
  });

  it("picks the nearest balloon through its leaves, not its root", () => {
    // Two balloons on the z axis; the root is large, the single leaf sits 0.5 m up.
    const poses = new Float32Array([0, 0, 0, 0, 0, 0, 1, 0, 0, 3, 0, 0, 0, 1]);
    const roots = [{ center: [0, 0.2, 0] as [number, number, number], radius: 1 }];
    const leaves = [[{ center: [0, 0.5, 0] as [number, number, number], radius: 0.3 }]];
    const hit = pickBalloon(ray([0, 0.5, 10], [0, 0, -1]), poses, 2, roots, leaves, null);
    expect(hit?.index).toBe(1);
    expect(hit?.distance).toBeCloseTo(6.7, 5);
    expect(hit?.point[2]).toBeCloseTo(3.3, 5);
    // Through the root but below the leaf: no hit.
    expect(pickBalloon(ray([0, -0.5, 10], [0, 0, -1]), poses, 2, roots, leaves, null)).toBeNull();
  });

  it("picks a shrunken balloon by its size now", () => {
    const poses = new Float32Array([0, 0, 0, 0, 0, 0, 1]);
    const roots = [{ center: [0, 0.2, 0] as [number, number, number], radius: 1 }];
    const leaves = [[{ center: [0, 0.5, 0] as [number, number, number], radius: 0.3 }]];
    const through = ray([0, 0.5, 10], [0, 0, -1]);
    expect(pickBalloon(through, poses, 1, roots, leaves, null, new Float32Array([1]))?.distance).toBeCloseTo(9.7, 5);
    // At half size the leaf sits 0.25 m up with a radius of 0.15: the ray at 0.5 m passes above it.
    expect(pickBalloon(through, poses, 1, roots, leaves, null, new Float32Array([0.5]))).toBeNull();
    const hit = pickBalloon(ray([0, 0.25, 10], [0, 0, -1]), poses, 1, roots, leaves, null, new Float32Array([0.5]));
    expect(hit?.distance).toBeCloseTo(9.85, 5);
  });

  it("finds the floor point under a ray", () => {
    const p = rayHorizontalPlane(ray([1, 5, 1], [1, -1, 0]), 0);
    expect(p).toEqual([6, 0, 1]);
    expect(rayHorizontalPlane(ray([0, 5, 0], [1, 0, 0]), 0)).toBeNull();
    expect(rayHorizontalPlane(ray([0, 5, 0], [0, 1, 0]), 0)).toBeNull();
  });

  it("picks the ribbon free end nearest the ray within a few pixels, never a knot", () => {
    // Two ribbons of 3 and 2 points hanging down the z = 0 plane; the camera 5 m away on z.
    const points = new Float32Array([0, 2, 0, 0, 1.5, 0, 0, 1, 0, 1, 2, 0, 1, 1.2, 0]);
    const offsets = new Uint32Array([0, 3, 5]);
    const perPixel = 0.001; // rad
    const at = (x: number, y: number) => ray([0, 1, -5], [x, y - 1, 5]);
    expect(pickRibbonEnd(at(0.01, 1), points, offsets, perPixel, 4)).toMatchObject({ ribbon: 0, point: 2, position: [0, 1, 0] });
    expect(pickRibbonEnd(at(1, 1.2), points, offsets, perPixel, 4)).toMatchObject({ ribbon: 1, point: 1 });
    expect(pickRibbonEnd(at(1, 1.2), points, offsets, perPixel, 4)!.distance).toBeCloseTo(Math.hypot(1, 0.2, 5), 4);
    // 0.05 m off at 5 m is 10 mrad: 10 pixels, beyond 4.
    expect(pickRibbonEnd(at(0.05, 1), points, offsets, perPixel, 4)).toBeNull();
    // The knots (first points) are not ends.
    expect(pickRibbonEnd(at(0, 2), points, offsets, perPixel, 4)).toBeNull();
    // Behind the camera: nothing.
    expect(pickRibbonEnd(ray([0, 1, 5], [0, 0, 1]), points, offsets, perPixel, 4)).toBeNull();
  });
});
