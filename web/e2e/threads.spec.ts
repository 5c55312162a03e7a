// The engine on several threads in the page: the app's server sends the
// cross-origin isolation headers, so the physics worker runs the threaded
// module with the thread count of `?threads=N`; the state hash after a number
// of steps is the native CLI's whatever that count; and a page served without
// the headers says so in one line and steps on one thread.

import { execFileSync } from "node:child_process";
import { mkdtempSync, rmSync, writeFileSync } from "node:fs";
import { tmpdir } from "node:os";
import { dirname, join } from "node:path";
import { fileURLToPath } from "node:url";
import type { Page } from "@playwright/test";
import { expect, open, pause, sceneHash, test } from "./fixtures";
import { serveDist } from "./serve.mjs";
import { NOT_ISOLATED_TEXT } from "../src/sim/threadPool";

const root = join(dirname(fileURLToPath(import.meta.url)), "..", "..");
const upBinary = join(root, "target", "release", "up");

/**
 * Small, with what makes the engine branch (web/determinism/scene.toml's
 * kind): two gases and sizes, tilted balloons, ribbons with and without a
 * weight, a fast throw into a wall, the pyramid ceiling.
 */
const SCENE = {
  room: { width: 4, depth: 4, wall_height: 2.5, ceiling: "pyramid", apex_height: 1 },
  balloons: [
    { count: 20, colors: ["red", "yellow", "blue"], size_in: 11, tilt_deg: 20, ribbon: { length_m: 1, segments: 12 } },
    { count: 8, colors: ["green"], size_in: 9, gas: "air", spawn: { min: [-1.5, 1, -1.5], max: [1.5, 1.5, 1.5] } },
    {
      count: 2,
      colors: ["#d4af37"],
      size_in: 16,
      velocity: [25, 3, -4],
      angular_velocity: [0, 5, 0],
      spawn: { min: [-1.6, 1.7, -1], max: [0, 2.4, 1] },
      ribbon: { length_m: 0.6, segments: 8, color: "red", weight_g: 5 },
    },
  ],
  sim: { seed: 7 },
};

/** The native run's state hash after exactly `steps` steps of SCENE (the CLI steps `--seconds / dt`, rounded). */
function nativeHash(steps: number, dt: number): string {
  const dir = mkdtempSync(join(tmpdir(), "up-threads-"));
  try {
    const scene = join(dir, "scene.json");
    writeFileSync(scene, JSON.stringify(SCENE));
    const out = execFileSync(upBinary, ["run", scene, "--seconds", String(steps * dt), "--json"], { encoding: "utf8" });
    const summary = JSON.parse(out.trim().split("\n").pop()!) as { steps: number; state_hash: string };
    expect(summary.steps, "the native run took the page's steps").toBe(steps);
    return summary.state_hash;
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
}

/** The page's threads, isolation and HUD line once its engine is ready. */
const threadsOf = (page: Page) =>
  page.evaluate(() => ({
    threads: window.__up!.threads(),
    isolated: window.__up!.isolated(),
    text: window.__up!.threadsText(),
    pageIsolated: self.crossOriginIsolated,
  }));

test("the page is cross-origin isolated and steps on the threads asked for", async ({ page }) => {
  await open(page, `&threads=2${sceneHash(SCENE)}`);
  expect(await threadsOf(page)).toEqual({ threads: 2, isolated: true, text: "Threads: 2", pageIsolated: true });
  const before = await page.evaluate(() => window.__up!.steps());
  await page.waitForFunction((b) => window.__up!.steps() > b + 10, before);
});

test("the panel's thread count restarts the engine on that many threads, with the scene shown", async ({ page }) => {
  await open(page, `&threads=2${sceneHash(SCENE)}`);
  const scene = await page.evaluate(() => window.__up!.sceneJson());
  const input = page.locator('[data-key="threads"] input');
  // The slider goes up to the machine's cores (two here): down to one.
  await input.fill("1");
  await input.press("Enter");
  await page.waitForFunction(() => window.__up!.threads() === 1);
  expect(await threadsOf(page)).toEqual({ threads: 1, isolated: true, text: "Threads: 1", pageIsolated: true });
  expect(await page.evaluate(() => window.__up!.sceneJson()), "the same scene").toBe(scene);
  // A fresh world of the scene's 30 balloons, stepping.
  await page.waitForFunction(() => window.__up!.balloonCount() === 30 && window.__up!.steps() > 10);
});

test("a thread count in the address that is not one is refused with a message, and the default used", async ({ page }) => {
  await open(page, `&threads=zero${sceneHash(SCENE)}`);
  const messages = await page.evaluate(() => window.__up!.messages());
  expect(messages.join("\n")).toContain("threads=zero is not a thread count: expected an integer from 1 to 64");
  expect((await threadsOf(page)).threads).toBeGreaterThanOrEqual(1);
});

/** Thread counts, and the pool's settings besides the page's default (sim/threadPool.ts's `requestedPool`). */
const RUNS: [number, string][] = [
  [1, ""],
  [2, ""],
  [4, ""],
  [2, "&pool=beside&spin=1"],
  [3, "&pool=here&spin=auto"],
  [4, "&pool=beside&spin=0"],
];

for (const [threads, pool] of RUNS) {
  test(`on ${threads} thread(s)${pool ? ` (${pool.slice(1)})` : ""} the state hash is the native run's after the same steps`, async ({ page }) => {
    await open(page, `&threads=${threads}${pool}${sceneHash(SCENE)}`);
    expect((await threadsOf(page)).threads).toBe(threads);
    await pause(page);
    const dt = await page.evaluate(() => JSON.parse(window.__up!.sceneJson()).sim.dt as number);
    const paused = await page.evaluate(() => window.__up!.stateHash());
    expect(paused.steps, "the world stepped before the pause").toBeGreaterThan(0);
    expect(paused.hash, `hash after ${paused.steps} steps on ${threads} thread(s)`).toBe(nativeHash(paused.steps, dt));
    // Two single steps on the paused world, as a user takes them.
    await page.keyboard.press("n");
    await page.waitForFunction((s) => window.__up!.steps() === s + 1, paused.steps);
    await page.keyboard.press("n");
    await page.waitForFunction((s) => window.__up!.steps() === s + 2, paused.steps);
    const stepped = await page.evaluate(() => window.__up!.stateHash());
    expect(stepped.steps).toBe(paused.steps + 2);
    expect(stepped.hash, `hash after ${stepped.steps} steps on ${threads} thread(s)`).toBe(nativeHash(stepped.steps, dt));
  });
}

test("make measure's window: the drawing held, the scene restarted and stepped on 2 threads to the native hash", async ({ page }) => {
  await open(page, `&threads=2${sceneHash(SCENE)}`);
  const dt = await page.evaluate(() => JSON.parse(window.__up!.sceneJson()).sim.dt as number);
  await page.evaluate(() => window.__up!.holdDrawing(true));
  const drawn = await page.evaluate(() => window.__up!.frames().drawn);
  const window_ = await page.evaluate(() => window.__up!.measureSteps(40));
  expect(window_.engineMs).toHaveLength(40);
  expect(window_.stateHash, "the window's hash after 40 steps from the scene's start").toBe(nativeHash(40, dt));
  expect(await page.evaluate(() => window.__up!.frames().drawn), "no frame drawn while held").toBe(drawn);
  await page.evaluate(() => window.__up!.holdDrawing(false));
  await page.waitForFunction((d) => window.__up!.frames().drawn > d, drawn);
});

test("make measure's window gives each thread's part of each stage on 2 threads, and the same hash", async ({ page }) => {
  // Enough balloons that the step is shared with the pool: a small one runs on the calling thread
  // alone, and a substep's staged run of 300 balloons can end before the pool's other thread arrives.
  await open(page, `&threads=2${sceneHash({ room: { width: 8, depth: 8 }, balloons: [{ count: 1500 }], sim: { seed: 3 } })}`);
  const plain = await page.evaluate(() => window.__up!.measureSteps(90));
  expect(plain.threadStages, "no figures unless asked").toEqual([]);
  const timed = await page.evaluate(() => window.__up!.measureSteps(90, true));
  expect(timed.stateHash, "timing the threads changes no result").toBe(plain.stateHash);
  const total = timed.threadStages.at(-1)!;
  expect(total.stage).toBe("total");
  expect(total.wall_ms).toBeCloseTo(timed.stageMeanMs.at(-1)![1], 6);
  expect(total.busy_ms).toHaveLength(2);
  expect(total.passes, "the step's parallel passes are counted").toBeGreaterThan(0);
  expect(total.busy_ms[1], "the pool's other thread ran some of them").toBeGreaterThan(0);
  // Each thread's parts add up to no more than the step. The pool's other
  // thread reads its own clock, which the page coarsens (5 µs where isolated):
  // each stage's part may be off by a reading at either end, and a stage's idle
  // time is never negative, so the bound allows two readings a stage.
  const stagesTimed = timed.threadStages.length - 1;
  const resolutionMs = 0.005;
  for (let t = 0; t < 2; t++) {
    const parts = total.busy_ms[t] + total.barrier_ms[t] + total.idle_ms[t];
    expect(parts, `thread ${t}'s parts of the step: ${JSON.stringify(timed.threadStages)}`).toBeLessThanOrEqual(
      total.wall_ms * 1.01 + stagesTimed * 2 * resolutionMs,
    );
  }
});

test.describe("served without the isolation headers", () => {
  let server: { url: string; close: () => Promise<void> };
  test.beforeAll(async () => {
    server = await serveDist({ isolated: false });
  });
  test.afterAll(async () => {
    await server?.close();
  });

  test("the page says in one line that it runs on one thread, and steps", async ({ page }) => {
    await page.goto(`${server.url}?test&threads=4${sceneHash(SCENE)}`);
    await page.waitForFunction(() => window.__up?.ready(), null, { timeout: 60_000, polling: 250 });
    expect(await threadsOf(page)).toEqual({ threads: 1, isolated: false, text: NOT_ISOLATED_TEXT, pageIsolated: false });
    await expect(page.locator("#hud-threads")).toHaveText(NOT_ISOLATED_TEXT);
    const before = await page.evaluate(() => window.__up!.steps());
    await page.waitForFunction((b) => window.__up!.steps() > b + 10, before);
    // The panel offers no thread count where there can be only one.
    await expect(page.locator('[data-key="threads"]')).toHaveCount(0);
  });
});
