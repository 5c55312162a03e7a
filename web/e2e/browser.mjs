// Debian's Chromium, headless, WebGL through SwiftShader (no GPU): the
// executable and flags shared by the Playwright tests (playwright.config.ts),
// the README's screenshot and the measurement. Never a downloaded browser.

import { chromium } from "@playwright/test";

export const executablePath = process.env.CHROMIUM ?? "/usr/bin/chromium";

export const CHROMIUM_ARGS = [
  "--no-sandbox",
  "--disable-gpu",
  "--disable-quic",
  "--no-first-run",
  "--disable-background-networking",
  "--disable-component-update",
  "--disable-sync",
  "--use-gl=angle",
  "--use-angle=swiftshader",
  "--enable-unsafe-swiftshader",
  "--ignore-gpu-blocklist",
];

/** Launches the browser (the scripts outside the test runner). */
export function launchChromium() {
  return chromium.launch({ executablePath, headless: true, args: CHROMIUM_ARGS });
}

/** The URL-safe base64 of `text` (a scene link's `#scene=` value). */
export function base64url(text) {
  return Buffer.from(text, "utf8").toString("base64").replace(/\+/g, "-").replace(/\//g, "_").replace(/=+$/, "");
}

/** The address path of the app with the end-to-end tests' hook (`window.__up`) turned on. */
export const TEST_PATH = "?test";
