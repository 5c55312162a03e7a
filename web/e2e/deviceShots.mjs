// Screenshots of the page as a phone upright and on its side and a tablet
// show it (touch emulation), after `npm run build`:
//   node e2e/deviceShots.mjs OUT_DIR [seconds] [DIST_DIR] [hash]
// DIST_DIR serves another build (a checkout's dist/, to compare before and after).

import { mkdirSync } from "node:fs";
import { dirname, join, resolve } from "node:path";
import { fileURLToPath } from "node:url";
import { preview } from "vite";
import { launchChromium, TEST_PATH } from "./browser.mjs";
import { PHONE, PHONE_LANDSCAPE, TABLET } from "./devices.mjs";

const here = dirname(fileURLToPath(import.meta.url));
const outDir = resolve(process.argv[2] ?? join(here, "out", "devices"));
const seconds = Number(process.argv[3] ?? 4);
const dist = process.argv[4] ? resolve(process.argv[4]) : undefined;
const hash = process.argv[5] ?? "";
mkdirSync(outDir, { recursive: true });

const server = await preview({
  root: join(here, ".."),
  ...(dist ? { build: { outDir: dist } } : {}),
  logLevel: "warn",
  preview: { host: "127.0.0.1", port: 0, strictPort: true, open: false },
});
const url = server.resolvedUrls.local[0];
const browser = await launchChromium();
try {
  for (const [name, options] of [
    ["phone-portrait", PHONE],
    ["phone-landscape", PHONE_LANDSCAPE],
    ["tablet", TABLET],
  ]) {
    const context = await browser.newContext(options);
    const page = await context.newPage();
    await page.goto(url + TEST_PATH + hash);
    await page.waitForFunction(() => window.__up?.ready(), null, { timeout: 120_000, polling: 250 });
    await page.waitForTimeout(seconds * 1000);
    const file = join(outDir, `${name}.png`);
    await page.screenshot({ path: file });
    console.log(`${name}: ${file}`);
    await context.close();
  }
} finally {
  await browser.close();
  await server.close();
}
