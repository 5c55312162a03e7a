// A bouquet twisted by hand: one of its balloons grabbed from above with the
// mouse and carried twice round the bouquet's middle leaves its ribbon wrapped
// round the others: its linking number with one of them (the engine's
// `ribbon_linking`, from the ribbons' points the page holds) is not 0 for the
// two seconds after it is let go, where before it was 0 with every one. The
// page's own gestures throughout: the arrow keys to look down on the
// bouquet, a press on the balloon, moves, a release. The twisted bouquet is photographed in the debug view, where
// ribbons touching each other are marked.

import { readFileSync } from "node:fs";
import type { Page, TestInfo } from "@playwright/test";
import type * as Glue from "../public/wasm/up_wasm";
import { expect, open, sceneHash, test } from "./fixtures";
import { RIBBON_POINT_STRIDE } from "../src/sim/frameLayout";

const WASM_DIR = new URL("../public/wasm/", import.meta.url);
const BOUQUET = new URL("../../assets/scenes/bouquet.toml", import.meta.url);

/** How far out from the weights' middle the balloon is carried, m: within its ribbon's reach from its weight at the height it is held (so the weight stays on the floor), past the bunch's middle. */
const RADIUS = 0.25;
/** Simulated seconds a turn takes: a hand's easy pace, about 0.4 m/s. */
const TURN_S = 4;
/** Mouse moves a turn: 15° each. */
const MOVES_PER_TURN = 24;
/** The 11" balloon's radius, m: it is held by its top. */
const BALLOON_RADIUS = 0.14;

/** The built engine in Node, the page's own module: it reads the scene file and counts the turns. */
async function engineGlue(): Promise<typeof Glue> {
  const glue = (await import(new URL("up_wasm.js", WASM_DIR).href)) as typeof Glue;
  glue.initSync({ module: readFileSync(new URL("up_wasm.wasm", WASM_DIR)) });
  return glue;
}

/** The bouquet scene (assets/scenes/bouquet.toml) as the engine writes it, for a link. */
function bouquetScene(glue: typeof Glue): unknown {
  const engine = new glue.Engine();
  engine.load_scene_toml(readFileSync(BOUQUET, "utf8"));
  const scene: unknown = JSON.parse(engine.scene_json());
  engine.free();
  return scene;
}

/** Ribbon `ribbon`'s linking number with each ribbon in the page's current frame (0 with itself). */
async function links(page: Page, glue: typeof Glue, ribbon: number): Promise<number[]> {
  const r = await page.evaluate(() => window.__up!.ribbonPoints());
  return Array.from(glue.ribbon_linking(new Float32Array(r.points), new Uint32Array(r.offsets), ribbon));
}

const simTime = (page: Page) => page.evaluate(() => window.__up!.clock().simTime);

/** Waits until the simulated clock reads `t` s. */
async function untilSimTime(page: Page, t: number, timeout = 60_000): Promise<void> {
  await page.waitForFunction((t) => window.__up!.clock().simTime >= t, t, { timeout, polling: 20 });
}

/** The camera's elevation above the horizontal through what it looks at, degrees. */
const elevation = (page: Page) =>
  page.evaluate(() => {
    const { position: p, target: t } = window.__up!.camera();
    const d = [p[0] - t[0], p[1] - t[1], p[2] - t[2]];
    return (Math.asin(d[1] / Math.hypot(d[0], d[1], d[2])) * 180) / Math.PI;
  });

/** Holds an arrow key until the camera's elevation passes `degrees` (up) or falls below it (down). */
async function tiltTo(page: Page, key: "ArrowUp" | "ArrowDown", degrees: number): Promise<void> {
  await page.keyboard.down(key);
  try {
    const poll = expect.poll(() => elevation(page), { timeout: 60_000, intervals: [50] });
    await (key === "ArrowUp" ? poll.toBeGreaterThanOrEqual(degrees) : poll.toBeLessThanOrEqual(degrees));
  } finally {
    await page.keyboard.up(key);
  }
}

/** Turns the mouse wheel over the view `clicks` times (nearer), and waits until the camera's damped move has stopped. */
async function zoomIn(page: Page, clicks: number): Promise<void> {
  const box = (await page.locator("canvas").first().boundingBox())!;
  await page.mouse.move(box.x + box.width / 2, box.y + box.height / 2);
  for (let i = 0; i < clicks; i++) await page.mouse.wheel(0, -200);
  let last = { at: "", drawn: 0 };
  await expect
    .poll(
      async () => {
        const now = await page.evaluate(() => ({ at: JSON.stringify(window.__up!.camera().position), drawn: window.__up!.frames().drawn }));
        const still = now.at === last.at && now.drawn >= last.drawn + 2;
        if (now.at !== last.at || still) last = now;
        return still;
      },
      { timeout: 60_000, intervals: [500] },
    )
    .toBe(true);
}

/** Pauses or resumes with the space key, as a user does. */
async function setPaused(page: Page, paused: boolean): Promise<void> {
  if ((await page.evaluate(() => window.__up!.paused())) === paused) return;
  await page.keyboard.press(" ");
  await page.waitForFunction((p) => window.__up!.paused() === p, paused);
}

/** A picture of the view as drawn a few frames on, without the overlays (the panel too), attached as `name`. */
async function photo(page: Page, testInfo: TestInfo, name: string): Promise<void> {
  const hidden = await page.addStyleTag({ content: "#hud, #help, #float-plot, #toolbar, .lil-gui.lil-root { visibility: hidden !important; }" });
  // A few frames for the camera's damping and the newest physics frame.
  const frames = await page.evaluate(() => window.__up!.frames().drawn);
  await page.waitForFunction((f) => window.__up!.frames().drawn >= f + 3, frames, { timeout: 60_000 });
  const path = testInfo.outputPath(`${name.replace(/[^a-z0-9]+/gi, "-")}.png`);
  await page.screenshot({ path, timeout: 60_000 });
  await testInfo.attach(name, { path, contentType: "image/png" });
  await hidden.evaluate((tag) => (tag as Element).remove());
}

// Fails today, so marked to be fixed: the page's carried ribbon catches on
// others (a link of 1 for a few tenths of a second, three times in the two
// turns) and slips off each time; after the release every link is 0. The
// engine's mirror of this gesture on the bouquet's first balloon
// (up-wasm `ribbon_links` tests, ignored) fails the same way. Ribbons wound
// round each other under a pull pass through (docs/physics.md, ribbons
// touching ribbons: limits as built).
test.fixme("a balloon carried twice round the bouquet leaves its ribbon wrapped round another", async ({ page }, testInfo) => {
  test.setTimeout(400_000);
  const glue = await engineGlue();
  await open(page, sceneHash(bouquetScene(glue)));
  expect(await page.evaluate(() => window.__up!.ribbonCount())).toBe(6);
  // The balloons rise on their ribbons and crowd over their weights.
  await untilSimTime(page, 10);

  // Looked down on, the drag plane (facing the camera through the grabbed point) is all but level.
  await tiltTo(page, "ArrowUp", 83);
  await zoomIn(page, 10);
  const start = await page.evaluate((stride) => {
    const up = window.__up!;
    const { points, offsets, bodies } = up.ribbonPoints();
    // The weights' middle: the free ends' mean.
    const middle = [0, 0, 0];
    for (let r = 0; r < bodies.length; r++) for (let k = 0; k < 3; k++) middle[k] += points[(offsets[r + 1] - 1) * stride + k] / bodies.length;
    // The balloon farthest out, whose top nothing hides from above.
    let best = { ribbon: -1, body: -1, out: -1, center: [0, 0, 0] };
    for (let r = 0; r < bodies.length; r++) {
      const c = up.balloonCenter(bodies[r])!;
      const out = Math.hypot(c[0] - middle[0], c[2] - middle[2]);
      if (out > best.out) best = { ribbon: r, body: bodies[r], out, center: c };
    }
    return { middle, ...best, pixel: up.project(best.center[0], best.center[1], best.center[2]) };
  }, RIBBON_POINT_STRIDE);
  const before = await links(page, glue, start.ribbon);
  expect(before, "the settled bouquet's ribbons are not twisted").toEqual([0, 0, 0, 0, 0, 0]);

  // The circle's points on the screen, at the height of the balloon's top (the grabbed point's).
  const height = start.center[1] + BALLOON_RADIUS;
  const angle0 = Math.atan2(start.center[2] - start.middle[2], start.center[0] - start.middle[0]);
  const onCircle = (a: number) =>
    page.evaluate(([x, y, z]) => window.__up!.project(x, y, z), [start.middle[0] + RADIUS * Math.cos(a), height, start.middle[2] + RADIUS * Math.sin(a)] as const);

  // The debug view from the start: the frames then carry where ribbons touch.
  await page.keyboard.press("d");
  await page.waitForFunction(() => window.__up!.debugView());
  // Frames draw nothing while the balloon is carried: SwiftShader's frame of
  // a second or more would hold up each pointer move as long, and the
  // carrying would take minutes of simulated time. The pointer's path to the
  // engine is the page's as ever (the pick reads the physics frames, not the picture).
  await page.evaluate(() => window.__up!.holdDrawing(true));
  await page.mouse.move(start.pixel.x, start.pixel.y);
  await page.mouse.down();
  // Half a second to the circle, then two turns, paced by the simulated clock.
  const first = await onCircle(angle0);
  let t = await simTime(page);
  for (let k = 1; k <= 6; k++) {
    await page.mouse.move(start.pixel.x + ((first.x - start.pixel.x) * k) / 6, start.pixel.y + ((first.y - start.pixel.y) * k) / 6);
    await untilSimTime(page, (t += 0.5 / 6));
  }
  const held = await page.evaluate((b) => window.__up!.balloonCenter(b)!, start.body);
  expect(Math.hypot(held[0] - start.middle[0] - RADIUS * Math.cos(angle0), held[2] - start.middle[2] - RADIUS * Math.sin(angle0)), "the balloon pressed on is the one carried").toBeLessThan(0.2);
  const carriedFrom = t;
  // The links after each move where they changed, and pictures the first time one is not 0.
  const seen: { t: number; links: number[] }[] = [];
  let photographed = false;
  for (let k = 1; k <= 2 * MOVES_PER_TURN; k++) {
    const p = await onCircle(angle0 + (2 * Math.PI * k) / MOVES_PER_TURN);
    await page.mouse.move(p.x, p.y);
    await untilSimTime(page, (t += TURN_S / MOVES_PER_TURN));
    const now = await links(page, glue, start.ribbon);
    if (JSON.stringify(now) !== JSON.stringify(seen.at(-1)?.links ?? before)) seen.push({ t: t - carriedFrom, links: now });
    if (!photographed && now.some((l) => l !== 0)) {
      // The first wrap, paused (the balloon still held), from above and from
      // the side, the view tilted down and back with the arrow keys: the
      // moves are aimed through the camera wherever it is, onto the drag
      // plane set at the press.
      photographed = true;
      await setPaused(page, true);
      await page.evaluate(() => window.__up!.holdDrawing(false));
      await photo(page, testInfo, "wrapped while carried, from above");
      await tiltTo(page, "ArrowDown", 40);
      await photo(page, testInfo, "wrapped while carried, from the side");
      await tiltTo(page, "ArrowUp", 83);
      await page.evaluate(() => window.__up!.holdDrawing(true));
      await setPaused(page, false);
    }
  }
  const carriedFor = (await simTime(page)) - carriedFrom;
  await page.mouse.up();
  // Left wrapped: not for a moment (a wrap that slips off shows for a few
  // tenths of a second), but every half second for two seconds after it is let go.
  const after: number[][] = [];
  for (let k = 1; k <= 4; k++) {
    await untilSimTime(page, t + 0.5 * k);
    after.push(await links(page, glue, start.ribbon));
  }
  await setPaused(page, true);
  const figures = { ribbon: start.ribbon, body: start.body, before, during: seen, after, carriedFor };
  console.log(`bouquet twist: ${JSON.stringify(figures)}`);
  await testInfo.attach("linking numbers", { body: JSON.stringify(figures, null, 2), contentType: "application/json" });

  // The bouquet from the side, nearer, paused: two seconds after it was let go.
  await page.evaluate(() => window.__up!.holdDrawing(false));
  await tiltTo(page, "ArrowDown", 40);
  await photo(page, testInfo, "two seconds after it was let go, from the side");

  expect(carriedFor, "two turns took about 2 × TURN_S of simulated time").toBeLessThan(2 * TURN_S * 1.5);
  expect(
    after.every((ls) => ls.some((l) => l !== 0)),
    `ribbon ${start.ribbon} (balloon ${start.body}) stays wrapped round another after two turns: linking numbers every half second after ${JSON.stringify(after)}`,
  ).toBe(true);
});
