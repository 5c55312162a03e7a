// Ribbons in the browser: drawn below the balloons at the ceiling, their
// particles in the debug view, and grabbed by the free end to pull a balloon down.

import { expect, open, pause, sceneHash, test } from "./fixtures";

/** Magenta: no balloon colour, wall, floor or background comes near its hue. */
const RIBBON_RGB: [number, number, number] = [255, 0, 255];

/** A small flat room, its balloons on magenta ribbons of `length` m. */
const ribbonScene = (count: number, length: number) => ({
  room: { width: 4, depth: 4, wall_height: 2.5, ceiling: "flat" },
  balloons: [{ count, colors: ["yellow", "blue"], ribbon: { length_m: length, color: "#ff00ff" } }],
});

test("ribbons are drawn below a pile at the ceiling", async ({ page }, testInfo) => {
  await open(page, sceneHash(ribbonScene(12, 1.2)));
  expect(await page.evaluate(() => window.__up!.ribbonCount())).toBe(12);
  // Rising takes about 2 s; then the pile settles under the ceiling.
  await page.waitForFunction(() => {
    const p = window.__up!.poses();
    for (let i = 1; i < p.length; i += 7) if (p[i] < 1.7) return false;
    return true;
  }, null, { timeout: 60_000, polling: 500 });
  await pause(page);
  await testInfo.attach("ribbons under the pile", { body: await page.screenshot(), contentType: "image/png" });
  const counts = await page.evaluate((rgb) => {
    const up = window.__up!;
    // Below the lowest balloon of the pile on the screen, down to the floor under it.
    let top = -Infinity;
    for (let i = 0; i < up.balloonCount(); i++) {
      const c = up.balloonCenter(i)!;
      top = Math.max(top, up.project(c[0], c[1] - 0.2, c[2]).y);
    }
    const floor = up.project(0, 0, 0).y;
    const region = { left: 0, top, right: window.innerWidth, bottom: floor };
    return {
      region,
      drawn: up.ribbonsDrawn(),
      withRibbons: up.colorPixels(rgb, 25, region, { balloons: true }),
      without: up.colorPixels(rgb, 25, region, { balloons: true, ribbons: true }),
    };
  }, RIBBON_RGB);
  expect(counts.drawn).toBe(12);
  expect(counts.region.bottom - counts.region.top, "a region below the pile").toBeGreaterThan(50);
  // Twelve ribbons of about 1 m, a pixel or two wide, seen from 6 m: hundreds of pixels.
  expect(counts.withRibbons.matching, JSON.stringify(counts)).toBeGreaterThan(300);
  expect(counts.without.matching, "nothing else there is of the ribbons' colour").toBeLessThan(20);
  // The debug view (D) shows every ribbon particle: 16 segments, 17 points a ribbon.
  await page.keyboard.press("d");
  await page.waitForFunction(() => window.__up!.ribbonParticlesDrawn() === 12 * 17, null, { timeout: 30_000 });
  // The panel's ribbon length re-ties them in the running world; 0 unties them.
  const steps = await page.evaluate(() => window.__up!.steps());
  const input = page.locator('[data-key="ribbon_length"] input').first();
  await input.fill("0");
  await input.press("Enter");
  await page.waitForFunction(() => window.__up!.ribbonsDrawn() === 0, null, { timeout: 30_000 });
  expect(await page.evaluate(() => window.__up!.balloonCount()), "the balloons stay").toBe(12);
  expect(await page.evaluate(() => window.__up!.steps()), "the world was not rebuilt (paused, its steps kept)").toBe(steps);
  const scene = JSON.parse(await page.evaluate(() => window.__up!.sceneJson())) as { balloons: { ribbon: { length_m: number; color: string } }[] };
  expect(scene.balloons[0].ribbon, "the scene and its link say so").toEqual(expect.objectContaining({ length_m: 0, color: "#ff00ff" }));
  expect(page.url()).toMatch(/#scene=/);
});

test("pulling a ribbon's free end down brings its balloon down", async ({ page }) => {
  await open(page, sceneHash(ribbonScene(2, 1)));
  await page.waitForFunction(() => window.__up!.balloonCenter(0)![1] > 1.8, null, { timeout: 60_000, polling: 500 });
  await page.waitForTimeout(1500); // the ribbons settle
  await pause(page);
  const start = await page.evaluate(() => {
    const up = window.__up!;
    const { end, body } = up.ribbonEnd(0)!;
    return { pixel: up.project(...end), body, height: up.balloonCenter(body)![1] };
  });
  await page.mouse.move(start.pixel.x, start.pixel.y);
  await page.mouse.down();
  await page.keyboard.press(" "); // resume while held
  for (let i = 1; i <= 10; i++) {
    await page.mouse.move(start.pixel.x, start.pixel.y + 15 * i);
    await page.waitForTimeout(80);
  }
  await page.waitForFunction((s) => window.__up!.balloonCenter(s.body)![1] < s.height - 0.5, start, { timeout: 30_000, polling: 250 });
  const held = await page.evaluate((body) => window.__up!.balloonCenter(body)![1], start.body);
  await page.mouse.up();
  expect(held, `the balloon came down from ${start.height.toFixed(2)} m`).toBeLessThan(start.height - 0.5);
  // Let go, it rises again on its ribbon.
  await page.waitForFunction((s) => window.__up!.balloonCenter(s.body)![1] > s.height - 0.2, start, { timeout: 30_000, polling: 250 });
});
