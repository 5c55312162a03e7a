import { describe, expect, it } from "vitest";
import { furniturePositions, furnitureUvs } from "./furniture";

describe("furniture geometry", () => {
  // Two triangles: one flat on the floor, one facing +x.
  const mesh = {
    vertices: new Float32Array([0, 0, 0, 1, 0, 0, 0, 0, 1, 2, 0, 0, 2, 1, 0, 2, 0, 1]),
    triangles: new Uint32Array([0, 2, 1, 3, 4, 5]),
  };

  it("unshares the vertices, triangle by triangle", () => {
    const p = furniturePositions(mesh);
    expect(p.length).toBe(18);
    expect(Array.from(p.slice(3, 6))).toEqual([0, 0, 1]);
    expect(Array.from(p.slice(9, 12))).toEqual([2, 0, 0]);
  });

  it("maps a top by x and z and a side by the axes across its normal, 2 a metre", () => {
    const uv = Array.from(furnitureUvs(furniturePositions(mesh)));
    // The floor triangle's second corner (0, 0, 1): u = x, v = z.
    expect(uv.slice(2, 4)).toEqual([0, 2]);
    // The +x face's second corner (2, 1, 0): u = z, v = y.
    expect(uv.slice(8, 10)).toEqual([0, 2]);
  });
});
