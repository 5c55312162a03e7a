// The furniture's triangles as the built engine hands them to the page: the
// birthday table's five pieces, closed and standing on the floor inside the
// room; none in a scene without furniture; a mesh piece refused in the
// browser. Needs the wasm build.

import { readFileSync } from "node:fs";
import { beforeAll, describe, expect, it } from "vitest";
import { loadBuiltEngine } from "./builtEngine";
import type { Engine } from "./engine";

let engine: Engine;

beforeAll(async () => {
  engine = await loadBuiltEngine();
});

const birthday = readFileSync(new URL("../../../assets/scenes/birthday.toml", import.meta.url), "utf8");

describe("furniture", () => {
  it("comes as the pieces' triangles, world frame, on the floor inside the room", () => {
    engine.loadSceneToml(birthday);
    const { vertices, triangles } = engine.furniture();
    // A table of five boxes and four chairs of six, 12 triangles a box.
    expect(triangles.length).toBe((5 + 4 * 6) * 12 * 3);
    expect(Math.max(...triangles)).toBe(vertices.length / 3 - 1);
    const ys = vertices.filter((_, i) => i % 3 === 1);
    expect(Math.min(...ys)).toBeCloseTo(0, 6);
    expect(Math.max(...ys)).toBeCloseTo(0.9, 5);
    const xs = vertices.filter((_, i) => i % 3 === 0);
    expect(Math.max(...xs.map(Math.abs))).toBeLessThan(3);
    // Building the scene fits the foil shapes' sphere trees (about a second
    // natively for its three, longer in wasm under a loaded test run).
  }, 30_000);

  it("is empty without furniture, and a mesh piece cannot be read in the browser", () => {
    engine.loadDefaultScene();
    expect(engine.furniture().triangles.length).toBe(0);
    expect(() => engine.loadSceneToml('[[furniture]]\nmesh = "chair.obj"\nposition = [0, 0, 0]\n')).toThrow(/furniture\[0\]\.mesh/);
  });
});
