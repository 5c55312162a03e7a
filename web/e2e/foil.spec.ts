// Foil balloons are drawn as foil: a scene's foil group gets an InstancedMesh
// of the engine's pillow of its own, one instance per foil balloon, next to
// the latex mesh; popping one and the debug view keep working.

import { count, expect, hideOverlays, open, pause, sceneHash, test } from "./fixtures";

const SCENE = {
  balloons: [
    { count: 5, colors: ["red", "blue"] },
    { count: 3, kind: "foil", colors: ["#d4af37", "#c0c0c0"] },
  ],
};

test("a foil group is drawn with its own instanced pillow, and its balloons pop", async ({ page, consoleErrors }, testInfo) => {
  await open(page, sceneHash(SCENE));
  await page.waitForFunction(() => window.__up!.foil().drawn === 3, null, { timeout: 30_000 });
  const foil = await page.evaluate(() => window.__up!.foil());
  expect(foil.meshes, "one foil mesh for the one foil group").toBe(1);
  expect(foil.bodies.length, "three bodies of the foil model").toBe(3);
  expect(await count(page)).toBe(8);

  await page.waitForTimeout(3000); // let them rise
  await pause(page);
  await hideOverlays(page);
  await testInfo.attach("latex and foil", { body: await page.screenshot(), contentType: "image/png" });

  // The debug view draws the foil balloons' trees like any other's.
  await page.keyboard.press("d");
  await page.waitForFunction(() => window.__up!.debugView());
  await page.waitForTimeout(500);
  await testInfo.attach("debug view with foil", { body: await page.screenshot(), contentType: "image/png" });
  await page.keyboard.press("d");
  await page.waitForFunction(() => !window.__up!.debugView());

  // Pop the foil balloon nearest the camera: nothing stands in front of it.
  const target = await page.evaluate(() => {
    const up = window.__up!;
    const cam = up.camera().position;
    let best: { x: number; y: number; d: number } | null = null;
    for (const i of up.foil().bodies) {
      const c = up.balloonCenter(i)!;
      const d = Math.hypot(c[0] - cam[0], c[1] - cam[1], c[2] - cam[2]);
      if (!best || d < best.d) best = { ...up.project(c[0], c[1], c[2]), d };
    }
    return best!;
  });
  await page.keyboard.down("Shift");
  await page.mouse.click(target.x, target.y);
  await page.keyboard.up("Shift");
  await page.waitForFunction(() => window.__up!.balloonCount() === 7, null, { timeout: 20_000 });
  await page.waitForFunction(() => window.__up!.foil().drawn === 2, null, { timeout: 20_000 });
  const after = await page.evaluate(() => window.__up!.foil());
  expect(after.bodies.length, "the popped balloon was a foil one").toBe(2);
  expect(consoleErrors).toEqual([]);
});

test("a scene without foil makes no foil mesh", async ({ page, consoleErrors }) => {
  await open(page, sceneHash({ balloons: [{ count: 4 }] }));
  const foil = await page.evaluate(() => window.__up!.foil());
  expect(foil).toEqual({ meshes: 0, drawn: 0, bodies: [] });
  expect(consoleErrors).toEqual([]);
});
