// Moving air on the page: the fan tool places a fan where the floor is
// clicked (and aims one by a drag), the engine then holds one more fan and
// the page draws it; "show air" fills the jet with motes; the door draught
// button opens a draught; the selected fan's speed is the panel's. Screenshots
// of the room with a fan and "show air" are attached (and kept in e2e/out).

import { expect, open, test } from "./fixtures";
import type { Page } from "@playwright/test";

// A click on the panel waits for the page's next frame, which SwiftShader may take many seconds to draw on a loaded machine.
test.use({ actionTimeout: 120_000 });

const air = (page: Page) => page.evaluate(() => window.__up!.air());

/** The client pixel of floor point (x, z). */
const floorPixel = (page: Page, x: number, z: number) => page.evaluate(([px, pz]) => window.__up!.project(px, 0, pz), [x, z]);

test("the fan tool places a fan on the clicked floor, a drag aims one, and show air draws the jet", async ({ page, consoleErrors }, testInfo) => {
  // Many steps, each waiting on frames that SwiftShader draws at about one a second on a loaded machine.
  test.setTimeout(480_000);
  await open(page);
  expect((await air(page)).sources, "the default room's air is still").toEqual([]);
  await page.locator('[data-key="fanTool"] input').check();
  await page.waitForFunction(() => window.__up!.air().tool);

  // A click: a fan over that spot, facing the room's centre.
  const spot = { x: 0.8, z: 1.2 };
  const pixel = await floorPixel(page, spot.x, spot.z);
  await page.mouse.click(pixel.x, pixel.y);
  await page.waitForFunction(() => window.__up!.air().sources.length === 1 && window.__up!.air().fansDrawn === 1);
  let state = await air(page);
  const fan = state.sources[0];
  expect(fan.kind).toBe("fan");
  expect(Math.hypot(fan.outlet[0] - spot.x, fan.outlet[2] - spot.z), `placed at (${fan.outlet[0].toFixed(3)}, ${fan.outlet[2].toFixed(3)})`).toBeLessThan(0.05);
  const toCentre = [-spot.x, -spot.z].map((c) => c / Math.hypot(spot.x, spot.z));
  expect(fan.aim[0] * toCentre[0] + fan.aim[2] * toCentre[1], "it faces the room's centre").toBeGreaterThan(0.99);
  expect(state.selected, "the new fan is the panel's").toBe(0);
  expect(state.drawCalls, "a fan is a handful of draw calls").toBeLessThanOrEqual(5);

  // A drag: a second fan, aimed from where the press went down toward where it ended.
  const from = await floorPixel(page, -1.2, 0.5);
  const to = await floorPixel(page, -1.2, -1.5);
  await page.mouse.move(from.x, from.y);
  await page.mouse.down();
  for (let i = 1; i <= 8; i++) {
    await page.mouse.move(from.x + ((to.x - from.x) * i) / 8, from.y + ((to.y - from.y) * i) / 8);
    await page.waitForTimeout(40);
  }
  await page.mouse.up();
  await page.waitForFunction(() => window.__up!.air().sources.length === 2);
  state = await air(page);
  const aimed = state.sources[1];
  expect(aimed.aim[2], `aimed along −z: ${aimed.aim.map((a) => a.toFixed(3))}`).toBeLessThan(-0.99);
  expect(state.fansDrawn).toBe(2);
  expect(state.selected).toBe(1);

  // The selected fan's speed from the panel.
  const speed = page.locator('[data-key="fanSpeed"] input').first();
  await speed.fill("5");
  await speed.press("Enter");
  await page.waitForFunction(() => window.__up!.air().sources[1]?.fullSpeed === 5);

  await page.locator('[data-key="fanTool"] input').uncheck();
  await page.locator('[data-key="showAir"] input').check();
  await page.waitForFunction(() => window.__up!.air().motesVisible > 100, null, { timeout: 60_000 });
  await page.waitForTimeout(1500);
  const shot = await page.screenshot({ path: testInfo.outputPath("fan-and-show-air.png") });
  await testInfo.attach("a fan placed, show air on", { body: shot, contentType: "image/png" });

  await page.locator('[data-key="door"] button').click();
  await page.waitForFunction(() => window.__up!.air().sources.some((s) => s.kind === "draught"));

  await page.locator('[data-key="removeFan"] button').click();
  await page.waitForFunction(() => window.__up!.air().sources.filter((s) => s.kind === "fan").length === 1);
  expect(consoleErrors, "no console errors").toEqual([]);
});
