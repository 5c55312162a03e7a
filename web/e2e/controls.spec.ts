// The controls of the README's table: arrow-key orbit, CTRL placement mode,
// grab / drag / pop, and the D key's debug view.

import { count, expect, hideOverlays, open, pause, sceneHash, test } from "./fixtures";

test("arrow keys orbit the view at constant distance", async ({ page }) => {
  await open(page);
  await pause(page);
  await hideOverlays(page);
  const still1 = await page.screenshot();
  const still2 = await page.screenshot();
  expect(still1.equals(still2), "paused, the view is still").toBe(true);
  const cam0 = await page.evaluate(() => window.__up!.camera());
  await page.keyboard.down("ArrowLeft");
  await page.waitForTimeout(500);
  await page.keyboard.up("ArrowLeft");
  await page.keyboard.down("ArrowUp");
  await page.waitForTimeout(300);
  await page.keyboard.up("ArrowUp");
  await page.waitForTimeout(200);
  const cam1 = await page.evaluate(() => window.__up!.camera());
  const moved = await page.screenshot();
  expect(moved.equals(still2), "the screenshots differ").toBe(false);
  type Camera = typeof cam0;
  const dist = (c: Camera) => Math.hypot(...c.position.map((x, i) => x - c.target[i]));
  expect(Math.abs(dist(cam1) - dist(cam0)), `distance kept: ${dist(cam0)} → ${dist(cam1)}`).toBeLessThan(1e-3);
  expect(cam1.position[1], "up raised the camera").toBeGreaterThan(cam0.position[1]);
  const az = (c: Camera) => Math.atan2(c.position[0] - c.target[0], c.position[2] - c.target[2]);
  expect(az(cam1), `left turned the azimuth from ${az(cam0)}`).toBeLessThan(az(cam0) - 0.02);
});

test("CTRL then a click adds exactly one balloon at the clicked spot", async ({ page }, testInfo) => {
  await open(page);
  await page.keyboard.press("Control");
  await page.waitForFunction(() => window.__up!.placement() && window.__up!.paused());
  await page.waitForTimeout(300);
  await testInfo.attach("placement mode", { body: await page.screenshot(), contentType: "image/png" });
  const n = await count(page);
  const target = { x: 1.2, z: -0.9 };
  const pixel = await page.evaluate((t) => window.__up!.project(t.x, 0, t.z), target);
  await page.mouse.click(pixel.x, pixel.y);
  await page.waitForFunction((m) => window.__up!.balloonCount() === m, n + 1);
  await page.waitForTimeout(700);
  expect(await count(page), "exactly one balloon added").toBe(n + 1);
  const pose = await page.evaluate(() => window.__up!.poses().slice(-7));
  expect(Math.hypot(pose[0] - target.x, pose[2] - target.z), `placed at (${pose[0].toFixed(3)}, ${pose[2].toFixed(3)})`).toBeLessThan(0.05);
  expect(pose[1], "on the floor").toBeLessThan(0.5);
  await page.keyboard.press("Control");
  await page.waitForFunction(() => !window.__up!.placement() && !window.__up!.paused());
});

test("a balloon can be grabbed, dragged and popped", async ({ page }) => {
  await open(page, sceneHash({ balloons: [{ count: 3 }], sim: { gravity: [0, -9.81, 0] } }));
  await page.waitForTimeout(3000); // let them reach the ceiling and settle a little
  const target = await page.evaluate(() => {
    const c = window.__up!.balloonCenter(0)!;
    return { ...window.__up!.project(c[0], c[1], c[2]), c };
  });
  await page.mouse.move(target.x, target.y);
  await page.mouse.down();
  for (let i = 1; i <= 10; i++) {
    await page.mouse.move(target.x + 12 * i, target.y + 15 * i);
    await page.waitForTimeout(60);
  }
  await page.waitForTimeout(600);
  const held = (await page.evaluate(() => window.__up!.balloonCenter(0)))!;
  await page.mouse.up();
  const moved = Math.hypot(held[0] - target.c[0], held[1] - target.c[1], held[2] - target.c[2]);
  expect(moved, "the grabbed balloon followed the mouse, m").toBeGreaterThan(0.3);

  await pause(page);
  const n = await count(page);
  const c = await page.evaluate(() => {
    const p = window.__up!.balloonCenter(0)!;
    return window.__up!.project(p[0], p[1], p[2]);
  });
  await page.keyboard.down("Shift");
  await page.mouse.click(c.x, c.y);
  await page.keyboard.up("Shift");
  await page.waitForFunction((m) => window.__up!.balloonCount() === m, n - 1);
});

test("the debug view draws the contact points, and only while it is on", async ({ page }, testInfo) => {
  // Sleeping balloons report no contacts: keep them awake.
  await open(page, sceneHash({ sim: { sleep: false } }));
  await page.waitForFunction(() => (window.__up!.stats()?.stats.contacts ?? 0) > 0, null, { timeout: 30_000 });
  expect((await page.evaluate(() => window.__up!.contacts())).inFrame, "no contacts travel while the debug view is off").toBe(0);
  await page.keyboard.press("d");
  await page.waitForFunction(() => window.__up!.contacts().drawn > 0, null, { timeout: 20_000 });
  await pause(page);
  const c = await page.evaluate(() => window.__up!.contacts());
  expect(c.drawn, "contacts are drawn").toBeGreaterThan(0);
  expect(c.drawn, "every contact of the frame is drawn").toBe(c.inFrame);
  expect(c.total, "the step's contacts include the frame's").toBeGreaterThanOrEqual(c.inFrame);
  await hideOverlays(page);
  const debugShot = await page.screenshot();
  await testInfo.attach("debug view", { body: debugShot, contentType: "image/png" });
  await page.keyboard.press("d");
  await page.keyboard.press("n"); // a fresh frame, without contacts
  await page.waitForFunction(() => window.__up!.contacts().inFrame === 0 && !window.__up!.debugView());
  expect((await page.evaluate(() => window.__up!.contacts())).drawn).toBe(0);
  await page.waitForTimeout(300);
  expect((await page.screenshot()).equals(debugShot), "the debug view changed the picture").toBe(false);
});
