import { describe, expect, it } from "vitest";
import * as THREE from "three";
import { FINISHES, FinishMaterials, SHEEN_AGED, SHEEN_FRESH, addLatexUv, latexHeight } from "./finishes";
import { normalMapFromHeight } from "./normalMap";
import { modelFinishes } from "./balloons";

describe("finishes", () => {
  it("are told apart by their materials' uniforms", () => {
    const made = new FinishMaterials();
    const latex = made.get("latex");
    const pearl = made.get("pearl");
    const foil = made.get("foil");
    expect(FINISHES).toEqual(["latex", "pearl", "foil"]);
    expect(made.get("latex")).toBe(latex);
    for (const m of [latex, pearl, foil]) expect(m.type).toBe("MeshPhysicalMaterial");
    expect([latex.metalness, latex.iridescence, latex.clearcoat]).toEqual([0, 0, 1]);
    expect(latex.transmission).toBeGreaterThan(0);
    expect(latex.normalMap).not.toBeNull();
    expect(pearl.iridescence).toBe(1);
    expect(pearl.metalness).toBe(0);
    expect([foil.metalness, foil.transmission]).toEqual([1, 0]);
    expect(foil.normalMap).not.toBeNull();
    expect(made.finishOf(pearl)).toBe("pearl");
    made.dispose();
  });

  it("latex grows velvety as it ages; pearl and foil keep their surface", () => {
    const made = new FinishMaterials();
    const latex = made.get("latex");
    const pearl = made.get("pearl");
    expect(latex.sheen).toBeCloseTo(SHEEN_FRESH);
    made.setAge(0.5);
    expect(latex.sheen).toBeCloseTo((SHEEN_FRESH + SHEEN_AGED) / 2);
    made.setAge(3);
    expect(latex.sheen).toBeCloseTo(SHEEN_AGED);
    expect(latex.clearcoat).toBeLessThan(1);
    expect(pearl.sheen).toBe(0);
    // Made after the ageing, a material starts aged.
    expect(made.get("foil").metalness).toBe(1);
    made.dispose();
  });

  it("the panel's override draws every latex model in one finish; foil models stay foil", () => {
    expect(modelFinishes(["latex", "pearl", "foil"], [false, false, true], null)).toEqual(["latex", "pearl", null]);
    expect(modelFinishes(["latex", "pearl", "foil"], [false, false, true], "pearl")).toEqual(["pearl", "pearl", null]);
  });

  it("pleats the neck and leaves the body smooth, seamlessly around", () => {
    for (const u of [0.1, 0.37, 0.8]) {
      expect(latexHeight(u, 0.2)).toBe(0);
      expect(latexHeight(u, 0.6)).toBe(0);
    }
    const neck = Array.from({ length: 50 }, (_, i) => latexHeight(i / 50, 0.93));
    expect(Math.max(...neck) - Math.min(...neck)).toBeGreaterThan(0.2);
    for (const v of [0.8, 0.9, 0.97]) expect(latexHeight(0, v)).toBeCloseTo(latexHeight(1, v), 9);
  });

  it("a flat height field is a flat normal map", () => {
    const t = normalMapFromHeight(() => 0.3, 5, 8);
    const data = t.image.data as Uint8Array;
    for (let i = 0; i < data.length; i += 4) expect([data[i], data[i + 1], data[i + 2]]).toEqual([128, 128, 255]);
    const sloped = normalMapFromHeight((u) => Math.sin(2 * Math.PI * u), 5, 8).image.data as Uint8Array;
    expect(new Set(Array.from({ length: 8 }, (_, i) => sloped[4 * i])).size).toBeGreaterThan(2);
  });

  it("maps the balloon's uv around its axis and down from the top", () => {
    const g = new THREE.BufferGeometry();
    g.setAttribute("position", new THREE.BufferAttribute(Float32Array.from([1, 1, 0, 0, 0, 1, -1, -1, 0]), 3));
    addLatexUv(g);
    const uv = g.getAttribute("uv");
    expect([uv.getX(0), uv.getY(0)]).toEqual([0.5, 0]);
    expect([uv.getX(1), uv.getY(1)]).toEqual([0.75, 0.5]);
    expect(uv.getY(2)).toBe(1);
  });
});
