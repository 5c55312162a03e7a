// The page as a visitor first sees it: it loads cleanly, draws the room and
// the balloons, the simulation runs, and it stays responsive under load.

import { count, DEFAULT_BALLOONS, expect, meanY, open, sceneHash, test } from "./fixtures";

test("page loads with no console errors", async ({ page, consoleErrors }) => {
  await open(page);
  await page.waitForTimeout(1500);
  expect(consoleErrors).toEqual([]);
  await expect(page.locator("#fatal"), "no fatal message").toBeHidden();
  await expect(page.locator("#message"), "no error banner").toBeHidden();
  await expect(page.locator("#hud-count")).toHaveText(`Balloons: ${DEFAULT_BALLOONS}`);
  await expect(page.locator("#hud-physics")).toHaveText(/^Physics: \d/);
  await expect(page.locator("#hud-fps")).toHaveText(/^FPS: \d+/);
});

test("a visitor's page has no test hook", async ({ page, consoleErrors }) => {
  const requested: string[] = [];
  page.on("request", (r) => requested.push(r.url()));
  await page.goto("/");
  // The app is up: the engine answered and balloons are counted in the HUD.
  await expect(page.locator("#hud-count")).toHaveText(`Balloons: ${DEFAULT_BALLOONS}`, { timeout: 60_000 });
  await expect(page.locator("#loading")).toBeHidden();
  expect(await page.evaluate(() => "__up" in window), "window.__up is absent").toBe(false);
  expect(requested.filter((u) => /testHook/i.test(u)), "the hook's module was not downloaded").toEqual([]);
  expect(consoleErrors).toEqual([]);
});

test("canvas is not blank and shows balloons", async ({ page }, testInfo) => {
  await open(page);
  await page.waitForTimeout(2500);
  const withBalloons = await page.evaluate(() => window.__up!.pixelStats(false));
  const without = await page.evaluate(() => window.__up!.pixelStats(true));
  await testInfo.attach("default view", { body: await page.screenshot(), contentType: "image/png" });
  expect(withBalloons.std, `the picture varies (std ${withBalloons.std.toFixed(1)})`).toBeGreaterThan(12);
  expect(withBalloons.saturatedFraction, "balloon colours on screen").toBeGreaterThan(0.004);
  expect(withBalloons.saturatedFraction, `hiding the balloons removes the colour (without: ${without.saturatedFraction})`).toBeGreaterThan(
    without.saturatedFraction * 2 + 0.002,
  );
});

test("balloons rise over time", async ({ page }) => {
  // A 30 m tall room: the rise takes ≈ 17 s, so a page that was slow to
  // become ready (a loaded machine) still catches the balloons rising.
  await open(page, sceneHash({ room: { wall_height: 30 }, balloons: [{ count: 20 }] }));
  const before = await meanY(page);
  const stepsBefore = await page.evaluate(() => window.__up!.steps());
  await page.waitForTimeout(2500);
  const after = await meanY(page);
  const steps = (await page.evaluate(() => window.__up!.steps())) - stepsBefore;
  expect(steps, "the simulation runs").toBeGreaterThan(20);
  expect(after, `mean height rose from ${before.toFixed(2)} m`).toBeGreaterThan(before + 0.3);
});

test("the page answers input and keeps drawing while a large scene runs in the worker", async ({ page }, testInfo) => {
  // SwiftShader on two shared cores draws such a frame in seconds.
  test.setTimeout(300_000);
  // 800 balloons: about 10 ms per step in the worker (the crowd geometry draws them).
  const scene = { room: { width: 10, depth: 10 }, balloons: [{ count: 800 }], sim: { sleep: false } };
  // A small canvas: the claim is about the main thread, not about pixels.
  await page.setViewportSize({ width: 480, height: 300 });
  await open(page, sceneHash(scene), 120_000);
  expect(await count(page)).toBe(800);
  await page.waitForFunction(() => (window.__up!.stats()?.stats.stages.at(-1)?.[1] ?? 0) > 1, null, { timeout: 30_000 });
  const before = await page.evaluate(() => ({ steps: window.__up!.steps(), frames: window.__up!.frames().drawn, camera: window.__up!.camera() }));
  // A key handled on the main thread changes state at once...
  await page.keyboard.press("d");
  expect(await page.evaluate(() => window.__up!.debugView()), "the D key's handler ran").toBe(true);
  await page.keyboard.press("d");
  // ...and a held arrow turns the view at the next frames, whatever the physics costs.
  await page.keyboard.down("ArrowLeft");
  await page.waitForFunction((x) => Math.abs(window.__up!.camera().position[0] - x) > 1e-3, before.camera.position[0], { timeout: 30_000 });
  await page.keyboard.up("ArrowLeft");
  // Frames kept coming while the worker stepped.
  await page.waitForFunction((b) => window.__up!.frames().drawn >= b.frames + 2 && window.__up!.steps() > b.steps + 10, before, { timeout: 30_000 });
  expect(await page.evaluate(() => window.__up!.paused()), "the simulation ran throughout").toBe(false);
  await testInfo.attach("large scene", { body: await page.screenshot(), contentType: "image/png" });
});
