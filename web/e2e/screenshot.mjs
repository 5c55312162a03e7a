// Takes the README's screenshot of the real app in headless Chromium:
// `node e2e/screenshot.mjs [out.png] [seconds] [hash]` after `npm run build`.

import { dirname, join } from "node:path";
import { fileURLToPath } from "node:url";
import { launchChromium, TEST_PATH } from "./browser.mjs";
import { serveDist } from "./serve.mjs";

const here = dirname(fileURLToPath(import.meta.url));
const outFile = process.argv[2] ?? join(here, "..", "..", "docs", "screenshot.png");
const seconds = Number(process.argv[3] ?? 8);
const hash = process.argv[4] ?? "";
const server = await serveDist();
const browser = await launchChromium();
try {
  const page = await browser.newPage({ viewport: { width: 1280, height: 720 } });
  await page.goto(server.url + TEST_PATH + hash);
  await page.waitForFunction(() => window.__up?.ready(), null, { timeout: 60_000 });
  await page.waitForTimeout(seconds * 1000);
  await page.screenshot({ path: outFile });
  console.log(`screenshot: ${outFile}`);
} finally {
  await browser.close();
  await server.close();
}
