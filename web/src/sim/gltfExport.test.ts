// The page's glTF export ("Export last 10 s (.glb)", up-export in the built
// engine, the code `up export-gltf` runs) passes the Khronos validator with
// no error on the default room, a bouquet, a room with foil balloons and
// the birthday table with its furniture.
// Needs the wasm build.

import { readFileSync } from "node:fs";
import { validateBytes } from "gltf-validator";
import { beforeAll, describe, expect, it } from "vitest";
import { loadBuiltEngine } from "./builtEngine";
import type { Engine } from "./engine";

let engine: Engine;

beforeAll(async () => {
  engine = await loadBuiltEngine();
});

const scene = (name: string) => readFileSync(new URL(`../../../assets/scenes/${name}`, import.meta.url), "utf8");

/** Records a frame every other step for `steps` steps, as the worker does for each frame it sends, and exports. */
function exportAfter(steps: number): Uint8Array {
  engine.recordExportFrame();
  for (let s = 0; s < steps; s += 2) {
    engine.step(2);
    engine.recordExportFrame();
  }
  return engine.exportGltf();
}

describe("the exported .glb passes the Khronos validator", () => {
  const cases: [string, () => void, string[]][] = [
    ["the default room", () => engine.loadDefaultScene(), ["KHR_materials_sheen"]],
    ["a bouquet", () => engine.loadSceneToml(scene("bouquet.toml")), ["KHR_materials_clearcoat"]],
    ["an evening with foil balloons", () => engine.loadSceneToml(scene("evening.toml")), ["KHR_materials_transmission"]],
    ["a birthday table with its chairs", () => engine.loadSceneToml(scene("birthday.toml")), ["KHR_materials_clearcoat"]],
  ];
  for (const [name, load, extensions] of cases) {
    it(name, async () => {
      load();
      const glb = exportAfter(60);
      const report = await validateBytes(glb, { maxIssues: 100 });
      const errors = report.issues.messages.filter((m) => m.severity === 0);
      console.log(`${name}: ${glb.length} bytes, ${report.issues.numErrors} errors, ${report.issues.numWarnings} warnings, ${report.issues.numInfos} infos`);
      expect(errors, JSON.stringify(errors.slice(0, 5))).toEqual([]);
      expect(report.issues.numErrors).toBe(0);
      expect(report.info?.animationCount).toBe(1);
      for (const e of extensions) expect(report.info?.extensionsUsed).toContain(e);
      // Building a scene fits its foil shapes' sphere trees: seconds in wasm
      // under a loaded test run.
    }, 30_000);
  }
});
