// Photo mode in headless Chromium (SwiftShader): the bake's time, the time to
// a number of samples, and screenshots of the live view and of the photo.
//   node e2e/photo.mjs [samples=64] [width=960] [height=600] [out-prefix=/tmp/photo] [seconds=8] [hash]
// after `npm run build`. Prints one JSON line. SwiftShader traces on the CPU:
// the times say how this machine does, not what a GPU does.

import { launchChromium, TEST_PATH } from "./browser.mjs";
import { serveDist } from "./serve.mjs";

const samples = Number(process.argv[2] ?? 64);
const width = Number(process.argv[3] ?? 960);
const height = Number(process.argv[4] ?? 600);
const prefix = process.argv[5] ?? "/tmp/photo";
const seconds = Number(process.argv[6] ?? 8);
const hash = process.argv[7] ?? "";

const server = await serveDist();
const browser = await launchChromium();
try {
  const page = await browser.newPage({ viewport: { width, height } });
  page.on("console", (m) => {
    if (m.type() === "error" || m.type() === "warning") console.error(`page: ${m.text()}`);
  });
  page.on("pageerror", (e) => console.error(`page error: ${e.message}`));
  const t0 = Date.now();
  const log = (what) => console.error(`${((Date.now() - t0) / 1000).toFixed(1)} s: ${what}`);
  await page.goto(server.url + TEST_PATH + hash);
  await page.waitForFunction(() => window.__up?.ready(), null, { timeout: 120_000 });
  // Balloons rise and gather first.
  await page.waitForTimeout(seconds * 1000);
  log("ready");
  // The 3D view only: the HUD, panel, help line and plot are page elements above it.
  await page.addStyleTag({ content: "#hud, #help, #float-plot, .lil-gui { visibility: hidden !important; }" });
  await page.screenshot({ path: `${prefix}-live.png` });
  log("live screenshot");
  const pressed = Date.now();
  await page.keyboard.press("p");
  await page.waitForFunction(() => window.__up.photo().samples >= 1, null, { timeout: 3_600_000, polling: 1000 });
  const bake = await page.evaluate(() => window.__up.photo().bake);
  log(`photo mode: ${JSON.stringify(bake)}`);
  const marks = {};
  for (const n of [...new Set([1, Math.min(16, samples), samples])]) {
    await page.waitForFunction((k) => window.__up.photo().samples >= k, n, { timeout: 3_600_000, polling: 1000 });
    marks[n] = (Date.now() - pressed) / 1000;
    log(`${n} samples`);
  }
  await page.screenshot({ path: `${prefix}-traced.png` });
  console.log(JSON.stringify({ width, height, bakeMs: Math.round(bake.ms), mergeMs: Math.round(bake.mergeMs), instances: bake.instances, triangles: bake.triangles, secondsToSamples: marks }));
} finally {
  await browser.close();
  await server.close();
}
