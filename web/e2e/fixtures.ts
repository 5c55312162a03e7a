// What the specs share: a `test` whose pages record their console errors and
// a screenshot when it fails (both attached to the report), opening the app
// with the test hook and a scene, and a few reads through the hook, `window.__up`.

import { test as base, expect, type Page } from "@playwright/test";
// The hook's type (window.__up), for the functions the specs evaluate in the page.
import type {} from "../src/app/testHook";
import { base64url, TEST_PATH } from "./browser.mjs";

export { expect };

export const DEFAULT_BALLOONS = 50;

export const test = base.extend<{ consoleErrors: string[]; failureScreenshot: void }>({
  // Every test records them (auto); a test that asks for them can assert on them.
  consoleErrors: [
    async ({ page }, use, testInfo) => {
      const errors: string[] = [];
      page.on("console", (m) => {
        if (m.type() === "error") errors.push(m.text());
      });
      page.on("pageerror", (e) => errors.push(`uncaught: ${e.message}`));
      await use(errors);
      if (testInfo.status !== testInfo.expectedStatus && errors.length > 0) {
        await testInfo.attach("console errors", { body: errors.join("\n"), contentType: "text/plain" });
      }
    },
    { auto: true },
  ],
  // Playwright's own failure screenshot gives up after 5 s, which a loaded
  // machine drawing through SwiftShader exceeds: this one waits longer.
  failureScreenshot: [
    async ({ page }, use, testInfo) => {
      await use();
      if (testInfo.status === testInfo.expectedStatus) return;
      const path = testInfo.outputPath("screenshot-at-failure.png");
      const taken = await page.screenshot({ path, timeout: 30_000 }).then(
        () => true,
        () => false,
      );
      if (taken) await testInfo.attach("screenshot at failure", { path, contentType: "image/png" });
    },
    { auto: true },
  ],
});

/** The address hash of a scene link. */
export function sceneHash(scene: unknown): string {
  return `#scene=${base64url(JSON.stringify(scene))}`;
}

/** Opens the app with the test hook (and `hash`), and waits until it has drawn balloons. */
export async function open(page: Page, hash = "", timeout = 60_000): Promise<void> {
  await page.goto(TEST_PATH + hash);
  await page.waitForFunction(() => window.__up?.ready(), null, { timeout, polling: 250 });
}

export const count = (page: Page) => page.evaluate(() => window.__up!.balloonCount());

/** Mean height of the balloons, m. */
export const meanY = (page: Page) =>
  page.evaluate(() => {
    const p = window.__up!.poses();
    let sum = 0;
    for (let i = 1; i < p.length; i += 7) sum += p[i];
    return sum / Math.max(1, p.length / 7);
  });

/** Pauses with the space key, as a user does, and lets the view settle. */
export async function pause(page: Page): Promise<void> {
  await page.keyboard.press(" ");
  await page.waitForFunction(() => window.__up!.paused());
  // Let OrbitControls' damping settle and the last frame arrive.
  await page.waitForTimeout(600);
}

/** Hides the HUD, the help line, the float plot and the toolbar, which change on their own (the FPS, the clock): screenshots then compare the 3D view only. */
export async function hideOverlays(page: Page): Promise<void> {
  await page.addStyleTag({ content: "#hud, #help, #float-plot, #toolbar { visibility: hidden !important; }" });
}
