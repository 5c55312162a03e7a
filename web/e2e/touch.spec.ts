// The page under a finger, on a phone-sized touch screen (390×844, mobile
// emulation): one finger orbits, the add button then a tap on the floor adds
// one balloon, a finger drags a balloon, a long press pops one, a tap
// selects one and shows its card, and the toolbar pauses and steps. Nothing
// here uses a key or a mouse.

import { count, expect, open, sceneHash, test } from "./fixtures";
import { PHONE } from "./devices.mjs";
import { Finger, line, reachableBalloon } from "./touch";

test.use(PHONE);

/** A few balloons under the ceiling, on their ribbons. */
const SCENE = { balloons: [{ count: 8 }] };

test("on a phone, every interaction has a finger's way: orbit, add, drag, long press, tap, pause and step", async ({ page, consoleErrors }, testInfo) => {
  test.setTimeout(300_000);
  await open(page, sceneHash(SCENE), 120_000);
  const finger = await Finger.on(page);
  await expect(page.locator("#toolbar")).toBeVisible();

  // One finger across empty room orbits the view (OrbitControls' touch rotation).
  const cam0 = await page.evaluate(() => window.__up!.camera());
  const start = { x: 195, y: 620 };
  expect(await page.evaluate((p) => document.elementFromPoint(p.x, p.y)?.id, start), "the drag starts on the room").toBe("view");
  await finger.drag(start, line(start, 90, 0));
  await page.waitForTimeout(500);
  const cam1 = await page.evaluate(() => window.__up!.camera());
  const turned = Math.hypot(...cam1.position.map((v, i) => v - cam0.position[i]));
  expect(turned, "a one-finger drag moved the camera, m").toBeGreaterThan(0.3);

  // The add button, then a tap on the floor: exactly one balloon, where tapped.
  await page.tap('#toolbar [data-action="add"]');
  await page.waitForFunction(() => window.__up!.placement() && window.__up!.paused());
  await expect(page.locator('#toolbar [data-action="add"]')).toHaveAttribute("aria-pressed", "true");
  await page.waitForTimeout(300);
  await testInfo.attach("placement on a phone", { body: await page.screenshot(), contentType: "image/png" });
  const n = await count(page);
  const target = { x: 0.6, z: -0.5 };
  const at = await page.evaluate((t) => window.__up!.project(t.x, 0, t.z), target);
  expect(await page.evaluate((p) => document.elementFromPoint(p.x, p.y)?.id, at), "the floor spot shows on the room").toBe("view");
  await finger.tap(at);
  await page.waitForFunction((m) => window.__up!.balloonCount() === m, n + 1);
  await page.waitForTimeout(700);
  expect(await count(page), "exactly one balloon added").toBe(n + 1);
  const pose = await page.evaluate(() => window.__up!.poses().slice(-7));
  expect(Math.hypot(pose[0] - target.x, pose[2] - target.z), `placed at (${pose[0].toFixed(3)}, ${pose[2].toFixed(3)})`).toBeLessThan(0.08);
  await page.tap('#toolbar [data-action="add"]');
  await page.waitForFunction(() => !window.__up!.placement() && !window.__up!.paused());

  // A finger on a balloon drags it.
  await page.waitForTimeout(1500);
  const grabbed = await reachableBalloon(page);
  expect(grabbed, "a balloon shows on the room").not.toBeNull();
  const before = (await page.evaluate((i) => window.__up!.balloonCenter(i), grabbed!.index))!;
  await finger.drag(grabbed!, line(grabbed!, 0, 120, 6), 60);
  const after = (await page.evaluate((i) => window.__up!.balloonCenter(i), grabbed!.index))!;
  const moved = Math.hypot(...after.map((v, i) => v - before[i]));
  expect(moved, "the dragged balloon followed the finger, m").toBeGreaterThan(0.2);

  // Pause by its button; a step by its button advances one step.
  await page.tap('#toolbar [data-action="togglePause"]');
  await page.waitForFunction(() => window.__up!.paused());
  await expect(page.locator('#toolbar [data-action="togglePause"]')).toHaveAttribute("aria-pressed", "true");
  await page.waitForTimeout(600);
  const steps0 = await page.evaluate(() => window.__up!.steps());
  await page.tap('#toolbar [data-action="step"]');
  await page.waitForFunction((s) => window.__up!.steps() > s, steps0);
  await page.waitForTimeout(400);
  expect(await page.evaluate(() => window.__up!.steps()), "one step, still paused").toBe(steps0 + 1);
  expect(await page.evaluate(() => window.__up!.paused())).toBe(true);

  // A long press on a balloon pops it.
  const victim = await reachableBalloon(page);
  expect(victim, "a balloon to pop shows on the room").not.toBeNull();
  const m = await count(page);
  await finger.hold(victim!, 1000);
  await page.waitForFunction((k) => window.__up!.balloonCount() === k, m - 1);
  await page.waitForTimeout(500);
  expect(await count(page), "exactly one popped").toBe(m - 1);

  // Play again by the same button.
  await page.tap('#toolbar [data-action="togglePause"]');
  await page.waitForFunction(() => !window.__up!.paused());
  await expect(page.locator('#toolbar [data-action="togglePause"]')).toHaveAttribute("aria-pressed", "false");

  // A tap on a balloon selects it: outlined, its card shown (the card is the step's: the world runs).
  await page.waitForTimeout(1000);
  const chosen = await reachableBalloon(page);
  expect(chosen, "a balloon to select shows on the room").not.toBeNull();
  await finger.tap(chosen!);
  await page.waitForFunction(() => window.__up!.physics().cardShown);
  await expect(page.locator("#balloon-card")).toBeVisible();
  expect(await count(page), "a tap pops nothing").toBe(m - 1);
  await testInfo.attach("a balloon selected on a phone", { body: await page.screenshot(), contentType: "image/png" });
  expect(consoleErrors).toEqual([]);
});
