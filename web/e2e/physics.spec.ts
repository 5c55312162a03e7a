// Seeing the physics: a click on a balloon selects it (outline, card, force
// arrows from the engine, live plots), Esc lets it go; the teaching scenes
// load from the panel's menu with their captions; helium lifts and air sinks
// in the arrows.

import type { Page } from "@playwright/test";
import { expect, open, pause, sceneHash, test } from "./fixtures";

/** Three balloons in a small flat room, at the ceiling within a couple of seconds. */
const SMALL = { room: { width: 4, depth: 4, wall_height: 2.5, ceiling: "flat" }, balloons: [{ count: 3, colors: ["yellow", "blue"] }] };

const physics = (page: Page) => page.evaluate(() => window.__up!.physics());

/** Clicks (press and release in place) on the centre of body `i` as drawn now. */
async function clickBalloon(page: Page, i: number): Promise<void> {
  const at = await page.evaluate((b) => {
    const c = window.__up!.balloonCenter(b)!;
    return window.__up!.project(c[0], c[1], c[2]);
  }, i);
  await page.mouse.click(at.x, at.y);
}

/** Chooses teaching scene `title` in the panel's menu and waits for its world and caption. */
async function chooseLesson(page: Page, title: string): Promise<void> {
  await page.locator('[data-key="lesson"] select').selectOption({ label: title });
  await page.waitForFunction((t) => window.__up!.physics().caption?.title === t && window.__up!.balloonCount() > 0, title, { timeout: 60_000, polling: 250 });
}

test("a click on a balloon shows its card, outline, force arrows and plots; Esc lets it go", async ({ page, consoleErrors }, testInfo) => {
  await open(page, sceneHash(SMALL));
  // At the ceiling and nearly still: the click lands where the balloon is drawn.
  await page.waitForFunction(() => {
    const p = window.__up!.poses();
    for (let i = 1; i < p.length; i += 7) if (p[i] < 1.9) return false;
    return true;
  }, null, { timeout: 60_000, polling: 500 });
  await clickBalloon(page, 0);
  await page.waitForFunction(() => {
    const s = window.__up!.physics();
    return s.selected === 0 && s.cardShown && s.arrows.some((a) => a.kind === "buoyancy");
  });
  const s = await physics(page);
  expect(s.outlined, "the selected balloon is outlined").toBe(true);
  expect(s.legendShown, "the arrows' legend is shown").toBe(true);
  expect(s.card!.gas).toBe("helium");
  expect(s.card!.net_lift_n, "a helium balloon lifts").toBeGreaterThan(0);
  const weight = s.arrows.find((a) => a.kind === "weight")!;
  const buoyancy = s.arrows.find((a) => a.kind === "buoyancy")!;
  expect(weight.force[1], "weight points down").toBeLessThan(0);
  expect(buoyancy.force[1], "buoyancy points up").toBeGreaterThan(0);
  expect(s.arrows.every((a) => a.body === 0), "only the selected balloon's arrows").toBe(true);
  // The card's net lift is the engine's buoyancy plus weight, whose arrows these are.
  expect(buoyancy.force[1] + weight.force[1]).toBeCloseTo(s.card!.net_lift_n, 3);
  const card = await page.locator("#balloon-card").textContent();
  for (const word of ["mass", "volume", "helium", "net lift", "speed", "height", "tilt", "terminal speed"]) expect(card).toContain(word);
  await page.screenshot({ path: "/tmp/physics-card.png" });
  // The selected balloon up close: its outline and arrows.
  const at = await page.evaluate(() => {
    const c = window.__up!.balloonCenter(0)!;
    return window.__up!.project(c[0], c[1], c[2]);
  });
  await page.screenshot({ path: "/tmp/physics-arrows.png", clip: { x: Math.max(0, at.x - 110), y: Math.max(0, at.y - 130), width: 220, height: 240 } });
  await testInfo.attach("card and arrows", { path: "/tmp/physics-card.png", contentType: "image/png" });

  // The plot fills as the simulated clock runs.
  await page.waitForFunction(() => window.__up!.physics().plot.points >= 20, null, { timeout: 60_000, polling: 500 });
  const plot = (await physics(page)).plot;
  expect(plot.shown).toBe(true);
  expect(plot.terminal, "the terminal speed of a lifting balloon is drawn upward").toBeGreaterThan(0);
  await page.waitForTimeout(600); // the plot redraws a few times a second
  await page.screenshot({ path: "/tmp/physics-plot.png" });
  await testInfo.attach("plots", { path: "/tmp/physics-plot.png", contentType: "image/png" });

  await page.keyboard.press("Escape");
  await page.waitForFunction(() => window.__up!.physics().selected === -1 && !window.__up!.physics().cardShown);
  expect((await physics(page)).arrows.length, "no arrows once deselected").toBe(0);
  expect(consoleErrors).toEqual([]);
});

test("every teaching scene loads from the menu, with its caption, without console errors", async ({ page, consoleErrors }) => {
  await open(page, sceneHash(SMALL));
  await page.waitForFunction(() => window.__up!.physics().lessons.length > 0);
  const lessons = (await physics(page)).lessons;
  const files = lessons.map((l) => l.file);
  for (const name of ["terminal-speed", "helium-and-air", "cold-room", "throw"]) expect(files).toContain(`scenes/learn-${name}.toml`);
  for (const lesson of lessons) {
    await chooseLesson(page, lesson.title);
    const s = await physics(page);
    expect(s.caption!.caption.length, `${lesson.file} has a caption`).toBeGreaterThan(40);
    await expect(page.locator("#scene-caption")).toContainText(lesson.title);
    await page.waitForTimeout(1500);
    await page.screenshot({ path: `/tmp/physics-${lesson.file.replace(/^scenes\/|\.toml$/g, "")}.png` });
    expect(consoleErrors, `after ${lesson.file}`).toEqual([]);
  }
  // The caption is dismissible.
  await page.locator("#scene-caption .close").click();
  await expect(page.locator("#scene-caption")).toBeHidden();
});

test("helium and air: a helium balloon's buoyancy points up, an air balloon's weight and buoyancy add up to a pull down", async ({ page }) => {
  await open(page, sceneHash(SMALL));
  await page.waitForFunction(() => window.__up!.physics().lessons.length > 0);
  const lesson = (await physics(page)).lessons.find((l) => l.file === "scenes/learn-helium-and-air.toml")!;
  expect(lesson).toBeTruthy();
  await chooseLesson(page, lesson.title);
  await page.locator('[data-key="forcesOnAll"] input').check();
  // The caption covers the room's top, where the helium balloon goes: out of the clicks' way.
  await page.locator("#scene-caption .close").click();
  await pause(page);
  const n = await page.evaluate(() => window.__up!.balloonCount());
  const seen = new Set<string>();
  for (let i = 0; i < n && seen.size < 2; i++) {
    await clickBalloon(page, i);
    // Paused: one step records the forces.
    await page.keyboard.press("n");
    await page.waitForFunction(
      (b) => {
        const s = window.__up!.physics();
        return s.selected === b && s.card?.index === b && s.arrows.some((a) => a.body === b && a.kind === "buoyancy");
      },
      i,
      { timeout: 30_000 },
    );
    const s = await physics(page);
    expect(s.forcesOnAll).toBe(true);
    const bodies = new Set(s.arrows.map((a) => a.body));
    expect(bodies.size, "arrows on every balloon").toBe(n);
    const mine = s.arrows.filter((a) => a.body === i);
    const buoyancy = mine.find((a) => a.kind === "buoyancy")!;
    const weight = mine.find((a) => a.kind === "weight")!;
    const gas = s.card!.gas;
    seen.add(gas);
    expect(buoyancy.force[1], `body ${i} (${gas}): buoyancy up`).toBeGreaterThan(0);
    if (gas === "helium") expect(buoyancy.force[1] + weight.force[1], `body ${i}: helium lifts`).toBeGreaterThan(0);
    if (gas === "air") expect(buoyancy.force[1] + weight.force[1], `body ${i}: air sinks`).toBeLessThan(0);
  }
  expect([...seen].sort()).toEqual(["air", "helium"]);
  await page.screenshot({ path: "/tmp/physics-forces-on-all.png" });
});

test("terminal speed: the selected balloon climbs at the engine's terminal speed, where its forces balance", async ({ page, consoleErrors }) => {
  await open(page, sceneHash(SMALL));
  await page.waitForFunction(() => window.__up!.physics().lessons.length > 0);
  const lesson = (await physics(page)).lessons.find((l) => l.file === "scenes/learn-terminal-speed.toml")!;
  expect(lesson).toBeTruthy();
  // Chosen while paused, the scene waits at its start: the balloon stays where the click aims,
  // and the plot follows it from rest once the clock runs again.
  await pause(page);
  await chooseLesson(page, lesson.title);
  await page.locator("#scene-caption .close").click();
  await clickBalloon(page, 0);
  await page.waitForFunction(() => window.__up!.physics().cardShown);
  await page.keyboard.press(" ");
  await page.waitForFunction(
    () => {
      const c = window.__up!.physics().card;
      return !!c && c.vertical_speed_m_s >= 0.995 * c.terminal_speed_m_s;
    },
    null,
    { timeout: 60_000, polling: 100 },
  );
  await page.keyboard.press(" ");
  const s = await physics(page);
  const weight = s.arrows.find((a) => a.kind === "weight")!;
  const drag = s.arrows.find((a) => a.kind === "drag")!;
  expect(drag.force[1], "drag holds the rising balloon back").toBeLessThan(0);
  // At 99.5 % of the terminal speed the net force is 1 % of the net lift: under 5 % of the weight.
  const net = s.arrows.filter((a) => a.body === 0).reduce((sum, a) => sum + a.force[1], 0);
  expect(Math.abs(net), `net vertical force ${net} N against a weight of ${weight.force[1]} N`).toBeLessThan(0.05 * Math.abs(weight.force[1]));
  // The plot's line is the card's terminal speed of a frame at most before (it moves a little with the air's density).
  expect(s.plot.terminal).toBeCloseTo(s.card!.terminal_speed_m_s, 3);
  await page.waitForTimeout(1500);
  await page.screenshot({ path: "/tmp/physics-terminal.png" });
  expect(consoleErrors).toEqual([]);
});
