// The page's layout as a visitor sees it at 960×600, 1280×800 and 1920×1080:
// the HUD, the panel, the float plot, the help line and a scene's caption
// (and, with a balloon selected, its card, its motion plot and the arrows'
// legend) each keep their own place: none covers another or runs off the
// window. And the default page loads without a console error or warning.

import type { Page } from "@playwright/test";
import { expect, open, sceneHash, test } from "./fixtures";

const SIZES: [number, number][] = [
  [960, 600],
  [1280, 800],
  [1920, 1080],
];

/** The overlays, by the name a failure reports. */
const OVERLAYS: Record<string, string> = {
  HUD: "#hud",
  panel: ".lil-gui.lil-root",
  "float plot": "#float-plot",
  "help line": "#help",
  caption: "#scene-caption",
  card: "#balloon-card",
  "motion plot": "#motion-plot",
  legend: "#force-legend",
  toolbar: "#toolbar",
};

interface Box {
  name: string;
  left: number;
  top: number;
  right: number;
  bottom: number;
}

/** The overlays shown now and their boxes in CSS pixels (a hidden one has no box). */
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

/** Each pair of boxes that share an area, as "a × b". */
function overlapping(boxes: Box[]): string[] {
  const pairs: string[] = [];
  for (let i = 0; i < boxes.length; i++) {
    for (let j = i + 1; j < boxes.length; j++) {
      const a = boxes[i];
      const b = boxes[j];
      const w = Math.min(a.right, b.right) - Math.max(a.left, b.left);
      const h = Math.min(a.bottom, b.bottom) - Math.max(a.top, b.top);
      if (w > 0 && h > 0) pairs.push(`${a.name} × ${b.name} (${Math.round(w)}×${Math.round(h)} px)`);
    }
  }
  return pairs;
}

/** At each size: exactly `expected` are shown, inside the window, and none overlaps another (soft: a run reports every size). */
async function expectApart(page: Page, expected: string[]): Promise<void> {
  for (const [width, height] of SIZES) {
    await page.setViewportSize({ width, height });
    // The layout follows at once; two frames let the app's resize handler run too.
    await page.evaluate(() => new Promise((done) => requestAnimationFrame(() => requestAnimationFrame(done))));
    const boxes = await shownBoxes(page);
    const at = `at ${width}×${height}`;
    expect.soft(boxes.map((b) => b.name).sort(), `${at}: the overlays shown`).toEqual([...expected].sort());
    for (const b of boxes) {
      const inside = b.left >= 0 && b.top >= 0 && b.right <= width && b.bottom <= height;
      expect.soft(inside, `${at}: the ${b.name} (${JSON.stringify(b)}) inside the window`).toBe(true);
    }
    expect.soft(overlapping(boxes), `${at}: overlays that cover one another`).toEqual([]);
  }
}

/**
 * Chromium's own note when, without a GPU (SwiftShader, --disable-gpu), its
 * compositor reads each WebGL frame back: a page that only clears a WebGL
 * canvas gets it too, so it says nothing about this page.
 */
const SOFTWARE_READBACK = /^\[\.WebGL-[0-9a-fx]+\]GL Driver Message \(OpenGL, Performance, [^)]*\): GPU stall due to ReadPixels/;

test("the default page loads without console errors or warnings, its overlays apart at each size", async ({ page }) => {
  const said: string[] = [];
  page.on("console", (m) => {
    if ((m.type() === "error" || m.type() === "warning") && !SOFTWARE_READBACK.test(m.text())) said.push(`${m.type()}: ${m.text()}`);
  });
  page.on("pageerror", (e) => said.push(`uncaught: ${e.message}`));
  await page.setViewportSize({ width: 1280, height: 800 });
  await open(page);
  // A few frames drawn: shadows, materials and the plot have run once.
  await page.waitForFunction(() => window.__up!.frames().drawn > 10, null, { timeout: 60_000 });
  expect.soft(said, "console errors and warnings on load").toEqual([]);
  await expectApart(page, ["HUD", "panel", "float plot", "help line"]);
});

/** One balloon held still mid-room (no gravity), under a caption as long as a teaching scene's. */
const CAPTION_SCENE = {
  about: {
    title: "Where the words go",
    caption:
      "A caption as long as a teaching scene's: it says what to watch in the room below, which balloon to click, " +
      "what its card and plot will show as it climbs, and why the arrows point the way they do. It wraps over " +
      "a few lines between the HUD and the panel, above the room, out of the way of the balloons.",
  },
  room: { width: 4, depth: 4, wall_height: 2.5, ceiling: "flat" },
  balloons: [{ count: 1, colors: ["red"], tilt_deg: 0, yaw_deg: 0, spawn: { min: [-0.3, 0.5, -0.3], max: [0.3, 1.5, 0.3] } }],
  sim: { gravity: [0, 0, 0] },
};

test("a scene's caption, and a selected balloon's card, motion plot and legend, keep apart from the rest at each size", async ({ page, consoleErrors }) => {
  await page.setViewportSize({ width: 1280, height: 800 });
  await open(page, sceneHash(CAPTION_SCENE));
  await expect(page.locator("#scene-caption")).toContainText("Where the words go");
  await expectApart(page, ["HUD", "panel", "float plot", "help line", "caption"]);

  await page.setViewportSize({ width: 1280, height: 800 });
  const at = await page.evaluate(() => {
    const c = window.__up!.balloonCenter(0)!;
    return window.__up!.project(c[0], c[1], c[2]);
  });
  await page.mouse.click(at.x, at.y);
  await page.waitForFunction(() => window.__up!.physics().cardShown);
  await expectApart(page, ["HUD", "panel", "help line", "caption", "card", "motion plot", "legend"]);
  expect(consoleErrors).toEqual([]);
});
