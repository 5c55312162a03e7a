// Looks in the live view: each balloon finish (latex, pearl, foil) loads and
// draws, and a balloon that hits a wall at 5 m/s is drawn flattened against
// it for a few frames and round again after (the physics stays rigid).

import { expect, hideOverlays, open, sceneHash, test } from "./fixtures";

const FINISHES_SCENE = {
  room: { width: 3, depth: 3, wall_height: 2.5, ceiling: "flat" },
  balloons: [
    { count: 3, colors: ["red"], finish: "latex", spawn: { min: [-1.4, 0.2, -0.4], max: [-0.5, 1.1, 0.4] } },
    { count: 3, colors: ["white"], finish: "pearl", spawn: { min: [-0.45, 0.2, -0.4], max: [0.45, 1.1, 0.4] } },
    { count: 3, colors: ["#c0c0c0"], finish: "foil", spawn: { min: [0.5, 0.2, -0.4], max: [1.4, 1.1, 0.4] } },
    { count: 1, kind: "foil", colors: ["#d4af37"], spawn: { min: [-0.4, 1.3, -0.4], max: [0.4, 2.2, 0.4] } },
  ],
};

test("each finish loads and draws with its own material", async ({ page, consoleErrors }, testInfo) => {
  // Three materials to compile: SwiftShader takes its time.
  await open(page, sceneHash(FINISHES_SCENE), 150_000);
  const looks = await page.evaluate(() => window.__up!.finishes());
  expect(looks.scene, "the engine reports each group's finish; a foil balloon's is foil").toEqual(["latex", "pearl", "foil", "foil"]);
  const byFinish = Object.fromEntries(looks.meshes.map((m) => [m.finish, m]));
  expect(Object.keys(byFinish).sort()).toEqual(["foil", "latex", "pearl"]);
  // Three of each drawn by its finish's mesh; the foil balloon by its pillow.
  for (const f of ["latex", "pearl", "foil"]) expect(byFinish[f].bodies, f).toBe(3);
  expect((await page.evaluate(() => window.__up!.foil())).drawn).toBe(1);
  expect(byFinish.latex).toMatchObject({ material: "MeshPhysicalMaterial", iridescence: 0, metalness: 0 });
  expect(byFinish.latex.transmission).toBeGreaterThan(0);
  expect(byFinish.pearl).toMatchObject({ iridescence: 1, metalness: 0 });
  expect(byFinish.foil).toMatchObject({ metalness: 1, transmission: 0 });

  // Drawn: the red latex balloons' colour is on the picture, and not without them.
  const red = await page.evaluate(() => window.__up!.colorPixels([1, 0, 0], 20));
  const hidden = await page.evaluate(() => window.__up!.colorPixels([1, 0, 0], 20, undefined, { balloons: true }));
  expect(red.matching).toBeGreaterThan(50);
  expect(hidden.matching).toBeLessThan(red.matching / 10);
  // And the whole picture changes where the balloons are.
  const withBalloons = await page.evaluate(() => window.__up!.pixelStats());
  const without = await page.evaluate(() => window.__up!.pixelStats(true));
  expect(Math.abs(withBalloons.mean - without.mean) + Math.abs(withBalloons.std - without.std)).toBeGreaterThan(0.5);
  await hideOverlays(page);
  await testInfo.attach("latex, pearl, chrome latex and a foil balloon", { body: await page.screenshot(), contentType: "image/png" });

  // The panel's finish draws every latex balloon in one finish; the foil balloon stays foil.
  await page.locator('[data-key="finish"] select').selectOption({ label: "pearl" });
  await page.waitForFunction(() => window.__up!.finishes().override === "pearl");
  const pearl = await page.evaluate(() => window.__up!.finishes());
  expect(pearl.meshes.map((m) => [m.finish, m.bodies])).toEqual([["pearl", 9]]);
  expect((await page.evaluate(() => window.__up!.foil())).drawn).toBe(1);
  await page.locator('[data-key="finish"] select').selectOption({ label: "as the scene says" });
  await page.waitForFunction(() => window.__up!.finishes().override === null);
  expect((await page.evaluate(() => window.__up!.finishes())).meshes.length).toBe(3);
  expect(consoleErrors).toEqual([]);
});

/**
 * A balloon flying into the +x wall at 5 m/s: gravity points along −x at
 * 80 m/s², so its buoyancy carries it that way at a terminal speed of 5 m/s
 * (1.75 m/s at 9.81), from 72 m away. The page opens with none; the panel
 * then adds it, so it hits while the test looks, however long the page took
 * to start.
 */
const WALL_SCENE = {
  room: { width: 80, depth: 3, wall_height: 3, ceiling: "flat" },
  balloons: [{ count: 0, colors: ["red"], tilt_deg: 0, yaw_deg: 0, spawn: { min: [-32.4, 1.0, -0.4], max: [-31.6, 1.9, 0.4] } }],
  sim: { gravity: [-80, 0, 0] },
};

test("a balloon hitting a wall at 5 m/s is drawn flattened for a few frames, then round", async ({ page, consoleErrors }) => {
  test.setTimeout(240_000);
  await open(page, sceneHash(WALL_SCENE), 150_000);
  const input = page.locator('[data-key="count"] input').first();
  await input.fill("1");
  await input.press("Enter");
  await page.waitForFunction(() => window.__up!.balloonCount() === 1, null, { timeout: 30_000 });
  // On its way: round.
  expect((await page.evaluate(() => window.__up!.squash(0))).drawn).toEqual([0, 0, 0, 0]);
  expect((await page.evaluate(() => window.__up!.poses()))[0], "not at the wall yet").toBeLessThan(39);
  // Frames at 60 fps after the impact: the dent as each would draw it.
  const ages = [0, 1, 2, 3, 4, 30].map((k) => (k * 1000) / 60);
  // The impact's dent is the deepest the page took: the bounces after it dent less, and on a slow
  // page the next bounce's dent may replace it (or it may spring back) before the test looks.
  await page.waitForFunction(() => window.__up!.squashPeak(0).madeAt !== null, null, { timeout: 120_000, polling: 50 });
  await page.waitForTimeout(1000);
  const hit = await page.evaluate((a) => ({ dent: window.__up!.squashPeak(0, a), x: window.__up!.poses()[0] }), ages);
  expect(hit.x, "at the +x wall (x = 40 m)").toBeGreaterThan(39);
  const depths = hit.dent.at.map(([x, y, z]) => Math.hypot(x, y, z));
  // Closed form: v·√(m/k) = 5 m/s · √(14.4 g / (2π · 0.14 m · 2 kPa)) = 1.43 cm; the engine's
  // impulse carries the drag and the solver's softness, so within a third.
  expect(depths[0]).toBeGreaterThan(0.0143 * 0.66);
  expect(depths[0]).toBeLessThan(0.0143 * 1.5);
  // Against the wall: the dent's normal is +x, its plane about a radius (0.14 m) out.
  const [nx, ny, nz, reach] = hit.dent.at[0];
  expect(nx / depths[0]).toBeGreaterThan(0.95);
  expect(Math.hypot(ny, nz) / depths[0]).toBeLessThan(0.3);
  expect(reach).toBeGreaterThan(0.1);
  expect(reach).toBeLessThan(0.2);
  // Flattened for the next frames at 60 fps, springing back: gone half a second on.
  for (let k = 1; k < 5; k++) {
    expect(depths[k], `frame ${k}`).toBeGreaterThan(0);
    expect(depths[k], `frame ${k}`).toBeLessThan(depths[k - 1]);
  }
  expect(depths[5]).toBe(0);

  // Pressed to the wall by its (eightfold) lift once the bounces are over, it rests there round:
  // the steady load dents it by less than a millimetre, which is not drawn.
  await page.waitForTimeout(4000);
  await expect
    .poll(() => page.evaluate(() => window.__up!.squash(0)), { timeout: 60_000, intervals: [250] })
    .toEqual({ drawn: [0, 0, 0, 0], at: [], madeAt: null });
  expect((await page.evaluate(() => window.__up!.poses()))[0]).toBeGreaterThan(39);
  expect(consoleErrors).toEqual([]);
});
