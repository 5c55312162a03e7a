// End-to-end tests: serves the built app (dist/) on a free localhost port,
// drives Debian's Chromium through playwright-core (headless, WebGL through
// SwiftShader), runs every test in tests.mjs, prints `N passed, N failed`,
// and always stops the browser and the server.
//
// Environment: CHROMIUM (default /usr/bin/chromium), E2E_ONLY (a substring of
// the test names to run), E2E_OUT (where failure screenshots go; e2e/out).

import { existsSync, mkdirSync, mkdtempSync, rmSync } from "node:fs";
import { tmpdir } from "node:os";
import { dirname, join } from "node:path";
import { fileURLToPath } from "node:url";
import { executablePath, launchChromium } from "./browser.mjs";
import { serve } from "./server.mjs";
import { tests } from "./tests.mjs";

const here = dirname(fileURLToPath(import.meta.url));
const dist = join(here, "..", "dist");
const out = process.env.E2E_OUT ?? join(here, "out");
const only = process.env.E2E_ONLY ?? "";
/** Per test unless it sets `timeoutMs`, ms: SwiftShader on two cores is slow. */
const TEST_TIMEOUT_MS = 90_000;

if (!existsSync(join(dist, "index.html"))) {
  console.error("e2e: dist/index.html is missing: run `npm run build` first");
  process.exit(1);
}
if (!existsSync(executablePath)) {
  console.error(`e2e: ${executablePath} is missing: install Debian's chromium (apt-get install -y chromium)`);
  process.exit(1);
}
mkdirSync(out, { recursive: true });

let server = null;
let browser = null;
const profile = mkdtempSync(join(tmpdir(), "up-e2e-"));

async function cleanup() {
  await browser?.close().catch(() => {});
  browser = null;
  await server?.close().catch(() => {});
  server = null;
  rmSync(profile, { recursive: true, force: true });
}

for (const signal of ["SIGINT", "SIGTERM"]) {
  process.on(signal, () => {
    cleanup().finally(() => process.exit(130));
  });
}

function withTimeout(promise, ms, name) {
  let timer;
  return Promise.race([
    promise,
    new Promise((_, reject) => {
      timer = setTimeout(() => reject(new Error(`${name}: timed out after ${ms / 1000} s`)), ms);
    }),
  ]).finally(() => clearTimeout(timer));
}

let passed = 0;
let failed = 0;
try {
  server = await serve(dist);
  // Playwright passes its own fresh --user-data-dir; TMPDIR is where temp files go.
  browser = await launchChromium({ ...process.env, TMPDIR: profile });
  console.log(`e2e: ${server.url} in Chromium ${browser.version()}`);

  for (const test of tests.filter((t) => t.name.includes(only))) {
    const context = await browser.newContext({ viewport: { width: 960, height: 600 }, deviceScaleFactor: 1 });
    const page = await context.newPage();
    const consoleErrors = [];
    page.on("console", (m) => {
      if (m.type() === "error") consoleErrors.push(m.text());
    });
    page.on("pageerror", (e) => consoleErrors.push(`uncaught: ${e.message}`));
    const started = Date.now();
    try {
      await withTimeout(test.run({ page, url: server.url, consoleErrors, out }), test.timeoutMs ?? TEST_TIMEOUT_MS, test.name);
      passed++;
      console.log(`ok - ${test.name} (${((Date.now() - started) / 1000).toFixed(1)} s)`);
    } catch (e) {
      failed++;
      console.log(`not ok - ${test.name}: ${e?.stack ?? e}`);
      if (consoleErrors.length) console.log(`  console errors: ${consoleErrors.join(" | ")}`);
      await page
        .screenshot({ path: join(out, `failed-${test.name.replace(/[^a-z0-9]+/gi, "-")}.png`) })
        .catch(() => {});
    } finally {
      await context.close().catch(() => {});
    }
  }
} catch (e) {
  failed++;
  console.log(`not ok - setup: ${e?.stack ?? e}`);
} finally {
  await cleanup();
}
console.log(`${passed} passed, ${failed} failed`);
process.exit(failed > 0 ? 1 : 0);
