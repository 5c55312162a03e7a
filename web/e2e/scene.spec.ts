// Scenes from the panel and from shared links, good and malformed.

import { count, DEFAULT_BALLOONS, expect, open, pause, sceneHash, test } from "./fixtures";

test("a change in the panel takes effect", async ({ page }) => {
  await open(page);
  const input = page.locator('[data-key="count"] input').first();
  await input.fill("12");
  await input.press("Enter");
  await page.waitForFunction(() => window.__up!.balloonCount() === 12, null, { timeout: 30_000 });
  await expect(page.locator("#hud-count")).toHaveText("Balloons: 12");
  expect(page.url(), "the scene is in the link").toMatch(/#scene=/);
  const scene = JSON.parse(await page.evaluate(() => window.__up!.sceneJson())) as { balloons: { count: number }[] };
  expect(scene.balloons.reduce((s, g) => s + g.count, 0)).toBe(12);
});

test("a shared link loads its scene", async ({ page }) => {
  const scene = { room: { width: 4, depth: 4, wall_height: 2.5, ceiling: "flat" }, balloons: [{ count: 9, colors: ["blue", "#ff8800"] }] };
  await open(page, sceneHash(scene));
  expect(await count(page)).toBe(9);
  await expect(page.locator("#message")).toBeHidden();
});

test("a malformed shared link shows an error and the default scene", async ({ page }, testInfo) => {
  await open(page, "#scene=%%%this-is-not-a-scene");
  await expect(page.locator("#message")).toBeVisible();
  await expect(page.locator("#message")).toHaveText(/shared link.*default scene/);
  expect(await count(page)).toBe(DEFAULT_BALLOONS);
  await testInfo.attach("malformed link", { body: await page.screenshot(), contentType: "image/png" });
  // A fresh document: a hash-only change would not reload the app.
  await page.goto("about:blank");

  await open(page, sceneHash({ room: { width: -1 } }));
  await expect(page.locator("#message")).toBeVisible();
  await expect(page.locator("#message")).toHaveText(/room\.width/);
  expect(await count(page)).toBe(DEFAULT_BALLOONS);
});

test("gravity from the panel changes the running world, and the link says so", async ({ page }) => {
  await open(page, sceneHash({ balloons: [{ count: 3 }] }));
  await pause(page);
  const steps = await page.evaluate(() => window.__up!.steps());
  const input = page.locator('[data-key="gravity"] input').first();
  await input.fill("1.62");
  await input.press("Enter");
  await page.waitForFunction(() => (JSON.parse(window.__up!.sceneJson()) as { sim: { gravity: number[] } }).sim.gravity[1] === -1.62, null, { timeout: 30_000 });
  expect(await page.evaluate(() => window.__up!.balloonCount()), "the balloons stay").toBe(3);
  expect(await page.evaluate(() => window.__up!.steps()), "the world was not rebuilt (paused, its steps kept)").toBe(steps);
  expect(page.url()).toMatch(/#scene=/);
  await expect(page.locator("#message")).toBeHidden();
});
