// The end-to-end tests (e2e/*.spec.ts): the built app (dist/) served by
// `vite preview`, driven in Debian's Chromium. Never a browser download: the
// executable is /usr/bin/chromium (or $CHROMIUM), and `npx playwright install`
// is not part of any setup.
//
//   npm run build && npx playwright test        (make test-e2e)
//
// Environment: CHROMIUM (the executable), UP_E2E_PORT (the preview server's
// port, 4173), CI (set: a stray `test.only` fails the run). The HTML report is
// written to e2e/out/report and never served (`npx playwright show-report e2e/out/report`).

import { existsSync } from "node:fs";
import { defineConfig } from "@playwright/test";
import { CHROMIUM_ARGS, executablePath } from "./e2e/browser.mjs";

if (!existsSync(executablePath)) {
  throw new Error(`${executablePath} is missing: install Debian's chromium (make setup-browser, or apt-get install -y chromium)`);
}

const port = Number(process.env.UP_E2E_PORT ?? 4173);
const baseURL = `http://127.0.0.1:${port}/`;

export default defineConfig({
  testDir: "e2e",
  outputDir: "e2e/out/results",
  // SwiftShader draws on the CPU: one page at a time keeps each test's timing honest.
  workers: 1,
  fullyParallel: false,
  forbidOnly: !!process.env.CI,
  retries: 0,
  // Per test unless it sets its own: a bound on a hang, not a speed claim. On a
  // loaded two-core machine SwiftShader draws about a frame a second and each
  // key press or screenshot takes seconds.
  timeout: 180_000,
  // The page's state follows the worker's frames: give a retried assertion a few of them.
  expect: { timeout: 15_000 },
  reporter: [["list"], ["html", { outputFolder: "e2e/out/report", open: "never" }]],
  use: {
    browserName: "chromium",
    baseURL,
    viewport: { width: 960, height: 600 },
    deviceScaleFactor: 1,
    headless: true,
    launchOptions: { executablePath, args: CHROMIUM_ARGS },
    actionTimeout: 30_000,
    navigationTimeout: 60_000,
    // A trace of every test, kept when it fails: its actions with their timings,
    // console, network and sources. No DOM snapshots or screencast: taking them
    // around every action slowed the page enough to time tests out on a loaded
    // machine. The screenshot at a failure is e2e/fixtures.ts's, which waits longer than Playwright's.
    trace: { mode: "retain-on-failure", screenshots: false, snapshots: false, sources: true },
  },
  webServer: {
    command: `npx vite preview --host 127.0.0.1 --port ${port} --strictPort`,
    url: baseURL,
    // Never another checkout's server on the same port: a busy port fails the run.
    reuseExistingServer: false,
    timeout: 60_000,
    stdout: "ignore",
    stderr: "pipe",
  },
});
