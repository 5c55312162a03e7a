// The panel's "Export last 10 s (.glb)": on a paused scene, the page's .glb
// is the native `up export-gltf` of the same scene and steps: the same
// nodes, and at every key the page recorded, every balloon and ribbon joint
// where the CLI has it at that time, within 1e-5 m. The .glb is read here
// (its JSON chunk and the floats its accessors point to).

import { execFileSync } from "node:child_process";
import { mkdtempSync, readFileSync, rmSync, writeFileSync } from "node:fs";
import { tmpdir } from "node:os";
import { dirname, join } from "node:path";
import { fileURLToPath } from "node:url";
import { expect, open, pause, sceneHash, test } from "./fixtures";

const root = join(dirname(fileURLToPath(import.meta.url)), "..", "..");
const upBinary = join(root, "target", "release", "up");

/** Small, with latex and foil balloons, ribbons and a weight. */
const SCENE = {
  room: { width: 4, depth: 4, wall_height: 2.5, ceiling: "pyramid", apex_height: 1 },
  balloons: [
    { count: 4, colors: ["red", "blue"], ribbon: { length_m: 0.8, segments: 6 } },
    { count: 2, kind: "foil", colors: ["#d4af37"] },
    { count: 1, colors: ["green"], finish: "pearl", ribbon: { length_m: 0.5, segments: 4, weight_g: 5 } },
  ],
  sim: { seed: 3 },
};

type Key = { t: number; p: [number, number, number] };

/** Each node's translation keys, by name, at the run's simulated time. */
function translationPaths(glb: Buffer): Map<string, Key[]> {
  expect(glb.toString("latin1", 0, 4)).toBe("glTF");
  const jsonLength = glb.readUInt32LE(12);
  const doc = JSON.parse(glb.toString("utf8", 20, 20 + jsonLength));
  const binAt = 20 + jsonLength + 8;
  const floats = (index: number): Float32Array => {
    const accessor = doc.accessors[index];
    const view = doc.bufferViews[accessor.bufferView];
    const start = binAt + (view.byteOffset ?? 0) + (accessor.byteOffset ?? 0);
    const copy = glb.subarray(start, start + view.byteLength);
    return new Float32Array(copy.buffer.slice(copy.byteOffset, copy.byteOffset + copy.byteLength));
  };
  const { start_s: start, sim_seconds_per_second: scale } = doc.scenes[0].extras.up;
  const animation = doc.animations[0];
  const paths = new Map<string, Key[]>();
  for (const channel of animation.channels) {
    if (channel.target.path !== "translation") continue;
    const sampler = animation.samplers[channel.sampler];
    const times = floats(sampler.input);
    const values = floats(sampler.output);
    const keys = Array.from(times, (t, k): Key => ({ t: start + t * scale, p: [values[3 * k], values[3 * k + 1], values[3 * k + 2]] }));
    paths.set(doc.nodes[channel.target.node].name, keys);
  }
  return paths;
}

/** The native export of SCENE over `steps` steps, every step a key. */
function nativeExport(steps: number, dt: number): Buffer {
  const dir = mkdtempSync(join(tmpdir(), "up-gltf-"));
  try {
    const scene = join(dir, "scene.json");
    const out = join(dir, "run.glb");
    writeFileSync(scene, JSON.stringify(SCENE));
    execFileSync(upBinary, ["export-gltf", scene, out, "--seconds", String(steps * dt), "--fps", String(1 / dt)], { encoding: "utf8" });
    return readFileSync(out);
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
}

test("the page's export of a paused scene is the CLI's for the same steps", async ({ page }) => {
  await open(page, sceneHash(SCENE));
  await pause(page);
  const paused = await page.evaluate(() => window.__up!.steps());
  // Two single steps on the paused world, as a user takes them.
  await page.keyboard.press("n");
  await page.waitForFunction((s) => window.__up!.steps() === s + 1, paused);
  await page.keyboard.press("n");
  await page.waitForFunction((s) => window.__up!.steps() === s + 2, paused);
  const steps = paused + 2;
  const dt = await page.evaluate(() => JSON.parse(window.__up!.sceneJson()).sim.dt as number);

  const downloading = page.waitForEvent("download");
  await page.locator('[data-key="exportGltf"] button').click();
  const download = await downloading;
  expect(download.suggestedFilename()).toMatch(/^up-.*\.glb$/);
  const fromPage = translationPaths(readFileSync((await download.path())!));
  const fromCli = translationPaths(nativeExport(steps, dt));

  expect([...fromPage.keys()].sort()).toEqual([...fromCli.keys()].sort());
  expect([...fromPage.keys()].filter((n) => n.startsWith("balloon-"))).toHaveLength(7);
  let compared = 0;
  for (const [name, keys] of fromPage) {
    const cli = fromCli.get(name)!;
    expect(keys.length, name).toBeGreaterThan(1);
    expect(keys[keys.length - 1].t, `${name} ends at the last step`).toBeCloseTo(steps * dt, 3);
    for (const key of keys) {
      const same = cli.find((c) => Math.abs(c.t - key.t) < 1e-4);
      expect(same, `${name} at ${key.t} s in the CLI's export`).toBeDefined();
      const gap = Math.hypot(...key.p.map((x, i) => x - same!.p[i]));
      expect(gap, `${name} at ${key.t} s`).toBeLessThan(1e-5);
      compared++;
    }
  }
  console.log(`compared ${compared} keys of ${fromPage.size} nodes over ${steps} steps`);
});
