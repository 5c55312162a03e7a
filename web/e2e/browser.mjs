// Debian's Chromium through playwright-core, headless, WebGL through
// SwiftShader (no GPU): shared by the tests, the screenshot and the measurement.

import { chromium } from "playwright-core";

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

/** Launches the browser; `env` goes to its process (TMPDIR for its temp files). */
export function launchChromium(env = process.env) {
  return chromium.launch({ executablePath, headless: true, args: CHROMIUM_ARGS, env });
}

/** The URL-safe base64 of `text` (a scene link's `#scene=` value). */
export function base64url(text) {
  return Buffer.from(text, "utf8").toString("base64").replace(/\+/g, "-").replace(/\//g, "_").replace(/=+$/, "");
}
