// The page on every screen from a small phone to a desktop: at 360×640,
// 390×844 and 768×1024 (touch, mobile) and 1280×800 and 1920×1080 (mouse),
// the overlays (HUD, panel, plots, card, caption, help line, the toolbar on
// touch screens) keep
// apart, inside the window, leaving at least 60 % of it to the room, the
// panel folded on the phones and the tablet; no console error or warning on
// any of them. And a scene shared from a desktop opens the same on a phone.

import type { Browser, Page } from "@playwright/test";
import { expect, open, sceneHash, test } from "./fixtures";
import { LAYOUT_SIZES, PHONE } from "./devices.mjs";
import { TEST_PATH } from "./browser.mjs";

/** The overlays, by the name a failure reports. */
const OVERLAYS: Record<string, string> = {
  HUD: "#hud",
  panel: ".lil-gui.lil-root",
  "float plot": "#float-plot",
  "motion plot": "#motion-plot",
  "help line": "#help",
  caption: "#scene-caption",
  card: "#balloon-card",
  legend: "#force-legend",
  toolbar: "#toolbar",
};

/** The share of the window the room must keep at load. */
const ROOM_SHARE = 0.6;

interface Box {
  name: string;
  left: number;
  top: number;
  right: number;
  bottom: number;
}

function shownBoxes(page: Page): Promise<Box[]> {
  return page.evaluate((overlays) => {
    const boxes: Box[] = [];
    for (const [name, selector] of Object.entries(overlays)) {
      const el = document.querySelector(selector);
      if (!el || getComputedStyle(el).visibility === "hidden") continue;
      const r = el.getBoundingClientRect();
      if (r.width > 0 && r.height > 0) boxes.push({ name, left: r.left, top: r.top, right: r.right, bottom: r.bottom });
    }
    return boxes;
  }, OVERLAYS);
}

function overlapping(boxes: Box[]): string[] {
  const pairs: string[] = [];
  for (let i = 0; i < boxes.length; i++) {
    for (let j = i + 1; j < boxes.length; j++) {
      const [a, b] = [boxes[i], boxes[j]];
      const w = Math.min(a.right, b.right) - Math.max(a.left, b.left);
      const h = Math.min(a.bottom, b.bottom) - Math.max(a.top, b.top);
      if (w > 0 && h > 0) pairs.push(`${a.name} × ${b.name} (${Math.round(w)}×${Math.round(h)} px)`);
    }
  }
  return pairs;
}

/** The window's area not under an overlay, counted on a 2 px grid (exact enough, and right even if boxes overlap). */
function roomShare(boxes: Box[], width: number, height: number): number {
  let free = 0;
  let all = 0;
  for (let y = 1; y < height; y += 2) {
    for (let x = 1; x < width; x += 2) {
      all++;
      if (!boxes.some((b) => x >= b.left && x < b.right && y >= b.top && y < b.bottom)) free++;
    }
  }
  return free / all;
}

/**
 * Chromium's own note when, without a GPU (SwiftShader), its compositor reads
 * each WebGL frame back: a page that only clears a WebGL canvas gets it too.
 */
const SOFTWARE_READBACK = /^\[\.WebGL-[0-9a-fx]+\]GL Driver Message \(OpenGL, Performance, [^)]*\): GPU stall due to ReadPixels/;

/** A page in a context of its own, recording its console's errors and warnings. */
async function devicePage(browser: Browser, options: object): Promise<{ page: Page; said: string[]; close: () => Promise<void> }> {
  const context = await browser.newContext({ ...options, baseURL: test.info().project.use.baseURL });
  const page = await context.newPage();
  const said: string[] = [];
  page.on("console", (m) => {
    if ((m.type() === "error" || m.type() === "warning") && !SOFTWARE_READBACK.test(m.text())) said.push(`${m.type()}: ${m.text()}`);
  });
  page.on("pageerror", (e) => said.push(`uncaught: ${e.message}`));
  return { page, said, close: () => context.close() };
}

for (const { name, options } of LAYOUT_SIZES) {
  test(`at ${name} the overlays keep apart, the room keeps ${ROOM_SHARE * 100} % of the window, and the console stays quiet`, async ({ browser }, testInfo) => {
    test.setTimeout(240_000);
    const { page, said, close } = await devicePage(browser, options);
    try {
      await open(page, "", 120_000);
      await page.waitForFunction(() => window.__up!.frames().drawn > 10, null, { timeout: 120_000 });
      const { width, height } = page.viewportSize()!;
      const layout = await page.evaluate(() => window.__up!.layout());
      const touch = "isMobile" in options;
      expect.soft(layout.compact, "the compact layout on phones and tablets only").toBe(touch);
      expect.soft(layout.panelClosed, "the panel folded on phones and tablets, open on desktops").toBe(touch);
      const boxes = await shownBoxes(page);
      for (const b of boxes) {
        const inside = b.left >= 0 && b.top >= 0 && b.right <= width && b.bottom <= height;
        expect.soft(inside, `the ${b.name} (${JSON.stringify(b)}) inside the window`).toBe(true);
      }
      expect.soft(boxes.map((b) => b.name).sort(), "the overlays shown at load").toEqual(
        // The toolbar on touch screens; a desktop with a mouse has the keys.
        (touch ? ["HUD", "panel", "help line", "toolbar"] : ["HUD", "panel", "float plot", "help line"]).sort(),
      );
      if (touch) {
        const hud = boxes.find((b) => b.name === "HUD")!;
        expect.soft(hud.bottom - hud.top, "the HUD is one line").toBeLessThan(40);
      }
      expect.soft(overlapping(boxes), "overlays that cover one another").toEqual([]);
      const share = roomShare(boxes, width, height);
      testInfo.annotations.push({ type: "room share", description: `${name}: ${(share * 100).toFixed(1)} %` });
      expect.soft(share, "the share of the window left to the room").toBeGreaterThanOrEqual(ROOM_SHARE);
      await testInfo.attach(`${name} at load`, { body: await page.screenshot(), contentType: "image/png" });
      expect(said, "console errors and warnings").toEqual([]);
    } finally {
      await close();
    }
  });
}

/** One balloon held still mid-room (no gravity), under a caption as long as a teaching scene's. */
const CAPTION_SCENE = {
  about: {
    title: "Where the words go",
    caption:
      "A caption as long as a teaching scene's: it says what to watch in the room below, which balloon to tap, " +
      "what its card and plot will show as it climbs, and why the arrows point the way they do.",
  },
  room: { width: 4, depth: 4, wall_height: 2.5, ceiling: "flat" },
  balloons: [{ count: 1, colors: ["red"], tilt_deg: 0, yaw_deg: 0, spawn: { min: [-0.3, 0.5, -0.3], max: [0.3, 1.5, 0.3] } }],
  sim: { gravity: [0, 0, 0] },
};

test.describe("on a phone", () => {
  test.use(PHONE);

  test("the HUD opens on a tap and folds on another; the help line gives way to the float plot; a selected balloon's card and plot keep apart", async ({ page, consoleErrors }) => {
    await open(page, sceneHash(CAPTION_SCENE), 120_000);
    await expect(page.locator("#scene-caption")).toContainText("Where the words go");
    await expect(page.locator("#help")).toBeVisible();
    await expect(page.locator("#float-plot")).toBeHidden();
    await page.tap("#hud");
    expect(await page.evaluate(() => window.__up!.layout().hudExpanded)).toBe(true);
    await expect(page.locator("#hud-stages")).toBeVisible();
    await expect(page.locator("#hud-cost"), "the HUD says the page draws for less").toContainText("Drawing for less");
    await page.tap("#hud");
    await expect(page.locator("#hud-stages")).toBeHidden();
    await page.tap("#help");
    await expect(page.locator("#help")).toBeHidden();
    await expect(page.locator("#float-plot")).toBeVisible();
    await page.tap("#scene-caption .close");

    const at = await page.evaluate(() => {
      const c = window.__up!.balloonCenter(0)!;
      return window.__up!.project(c[0], c[1], c[2]);
    });
    await page.touchscreen.tap(at.x, at.y);
    await page.waitForFunction(() => window.__up!.physics().cardShown);
    await expect(page.locator("#motion-plot")).toBeVisible();
    await expect(page.locator("#float-plot")).toBeHidden();
    expect(overlapping(await shownBoxes(page)), "overlays that cover one another").toEqual([]);
    expect(consoleErrors).toEqual([]);
  });
});

test("a scene shared from a desktop opens the same on a phone, its panel folded", async ({ browser, page, consoleErrors }) => {
  test.setTimeout(240_000);
  await page.setViewportSize({ width: 1280, height: 800 });
  await open(page);
  const input = page.locator('[data-key="count"] input').first();
  await input.fill("7");
  await input.press("Enter");
  await page.waitForFunction(() => window.__up!.balloonCount() === 7, null, { timeout: 30_000 });
  await page.locator(".lil-gui button", { hasText: "copy share link" }).click();
  await expect(page).toHaveURL(/#scene=/);
  const link = page.url();
  expect(link, "the link opens the page with the test hook").toContain(TEST_PATH);
  const desktopScene = await page.evaluate(() => window.__up!.sceneJson());

  const phone = await browser.newContext(PHONE);
  try {
    const onPhone = await phone.newPage();
    await onPhone.goto(link);
    await onPhone.waitForFunction(() => window.__up?.ready(), null, { timeout: 120_000, polling: 250 });
    expect(await onPhone.evaluate(() => window.__up!.balloonCount())).toBe(7);
    expect(JSON.parse(await onPhone.evaluate(() => window.__up!.sceneJson())), "the same scene").toEqual(JSON.parse(desktopScene));
    const layout = await onPhone.evaluate(() => window.__up!.layout());
    expect(layout.compact).toBe(true);
    expect(layout.panelClosed, "the panel folded").toBe(true);
    await expect(onPhone.locator("#message")).toBeHidden();
  } finally {
    await phone.close();
  }
  expect(consoleErrors).toEqual([]);
});
