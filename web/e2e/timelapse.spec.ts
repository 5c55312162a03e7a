// Time-lapse: the panel's ×3 600 runs hours of simulated time in seconds, the
// HUD's clock says so, the balloons shrink as their helium leaves, and the
// float plot draws where they are against simulated time.

import { expect, open, test } from "./fixtures";

/** "Clock h:mm:ss …" to seconds. */
function clockSeconds(text: string): number {
  const m = /^Clock (\d+):(\d\d):(\d\d)/.exec(text);
  if (!m) throw new Error(`the HUD's clock line reads "${text}"`);
  return Number(m[1]) * 3600 + Number(m[2]) * 60 + Number(m[3]);
}

test("×3 600 runs an hour in seconds: the clock, shrinking balloons, the plot", async ({ page, consoleErrors }, testInfo) => {
  await open(page);
  const before = await page.evaluate(() => window.__up!.clock());
  expect(before.rate).toBe(1);
  expect(before.text).toMatch(/^Clock 0:00:\d\d · 20\.0 °C · real time$/);
  expect(before.simTime, "real time at first").toBeLessThan(120);
  const scales0 = await page.evaluate(() => window.__up!.bodyScales());
  expect(scales0.length).toBe(await page.evaluate(() => window.__up!.balloonCount()));
  for (const s of scales0) expect(s, "filled to the shape's size").toBeGreaterThan(0.98);

  await page.locator('[data-key="timeLapse"] select').selectOption({ label: "×3\u2009600" });
  await page.waitForFunction(() => window.__up!.clock().rate === 3600, null, { timeout: 30_000 });
  // A few seconds of the page: while the balloons rise the clock runs slower, then it jumps.
  await page.waitForTimeout(5_000);
  await expect
    .poll(async () => clockSeconds(await page.locator("#hud-clock").innerText()), { timeout: 120_000, intervals: [500] })
    .toBeGreaterThan(10 * 60);
  await page.waitForFunction(() => window.__up!.clock().simTime > 3700, null, { timeout: 120_000, polling: 500 });
  const after = await page.evaluate(() => window.__up!.clock());
  expect(after.text, "the pace asked and achieved").toMatch(/×3\u2009600 \(now ×[\d\u2009]+\)$/);
  expect(after.achievedRate, "the clock jumps while the pile sleeps").toBeGreaterThan(60);

  const scales = await page.evaluate(() => window.__up!.bodyScales());
  for (const s of scales) {
    expect(s, "an hour of helium loss shrinks every balloon").toBeLessThan(1);
    expect(s).toBeGreaterThan(0.5);
  }

  const plot = await page.evaluate(() => window.__up!.plot());
  expect(plot.samples.length, "a look every simulated minute").toBeGreaterThan(20);
  const last = plot.samples[plot.samples.length - 1];
  expect(last.t).toBeGreaterThan(3000);
  expect(last.ceiling + last.hovering + last.floor).toBeCloseTo(1, 5);
  expect(last.ceiling, "after an hour the balloons are still up").toBeGreaterThan(0.8);
  // An hour on a two-hour axis: the ceiling's line, 2 px thick, across half the plot's 244 px.
  expect(plot.drawnPixels, `lines are drawn in the plot's ${plot.pixels} pixels`).toBeGreaterThan(300);
  expect(plot.ceilingPixels, "the ceiling's line is drawn").toBeGreaterThan(150);
  await testInfo.attach("after an hour at ×3 600", { body: await page.screenshot(), contentType: "image/png" });

  // Back to real time: the clock runs at 1 s a second again.
  await page.locator('[data-key="timeLapse"] select').selectOption({ label: "real time" });
  await page.waitForFunction(() => window.__up!.clock().rate === 1, null, { timeout: 30_000 });
  const t0 = await page.evaluate(() => window.__up!.clock().simTime);
  await page.waitForTimeout(2_000);
  const t1 = await page.evaluate(() => window.__up!.clock().simTime);
  expect(t1 - t0, "real time again").toBeLessThan(10);
  expect(consoleErrors).toEqual([]);
});
