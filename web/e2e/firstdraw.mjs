// How soon the default scene starts drawing on a mid-range phone's stand-in:
// Chromium's mobile emulation (390×844, touch) with the CPU slowed 4× (CDP
// Emulation.setCPUThrottlingRate), from the page's first paint to its first
// frame with balloons; each run in a fresh context (a cold cache). After
// `npm run build`:
//
//   node e2e/firstdraw.mjs [--runs 3] [--rate 4]
//   --dist DIR     serves another build than dist/
//
// SwiftShader draws on this machine's CPU: the figures bound a phone's from
// above (a phone's GPU draws the frames), and say nothing of its frame rate.

import { launchChromium, TEST_PATH } from "./browser.mjs";
import { PHONE } from "./devices.mjs";
import { dirname, join, resolve } from "node:path";
import { fileURLToPath } from "node:url";
import { preview } from "vite";

const args = process.argv.slice(2);
const arg = (name, fallback) => {
  const i = args.indexOf(`--${name}`);
  return i >= 0 ? Number(args[i + 1]) : fallback;
};
const runs = arg("runs", 3);
const rate = arg("rate", 4);
const distAt = args.indexOf("--dist");
const dist = distAt >= 0 ? resolve(args[distAt + 1]) : undefined;

const vite = await preview({
  root: join(dirname(fileURLToPath(import.meta.url)), ".."),
  ...(dist ? { build: { outDir: dist } } : {}),
  logLevel: "warn",
  preview: { host: "127.0.0.1", port: 0, strictPort: true, open: false },
});
const server = { url: vite.resolvedUrls.local[0], close: () => vite.close() };
const browser = await launchChromium();

/** A phone page on the default scene with the CPU slowed `slowdown`×, ready. */
async function phonePage(slowdown) {
  const context = await browser.newContext(PHONE);
  const page = await context.newPage();
  const cdp = await context.newCDPSession(page);
  await cdp.send("Emulation.setCPUThrottlingRate", { rate: slowdown });
  await page.goto(server.url + TEST_PATH);
  await page.waitForFunction(() => window.__up?.ready(), null, { timeout: 300_000, polling: 100 });
  return { page, context };
}

// Times on the page's clock, ms: its first paint, the stage built (ms it took), the balloon
// model's file in, the engine's first world and the model ready, the first frame with
// balloons (and its render call's ms), and that frame after the first paint.
const ms = (x) => (x === null || x === undefined ? null : Math.round(x));
try {
  for (const slowdown of [rate, 1]) {
    for (let r = 0; r < runs; r++) {
      const { page, context } = await phonePage(slowdown);
      const t = await page.evaluate(() => ({
        ...window.__up.firstDraw(),
        modelFetch: performance.getEntriesByType("resource").find((e) => /\.obj$/.test(e.name))?.responseEnd,
      }));
      const row = {
        slowdown,
        firstPaintMs: ms(t.firstPaint),
        stageMs: ms(t.stageMs),
        modelFileMs: ms(t.modelFetch),
        engineMs: ms(t.engineAt),
        modelMs: ms(t.assetsAt),
        firstDrawMs: ms(t.firstDrawAt),
        firstRenderCallMs: ms(t.firstRenderMs),
        afterPaintMs: ms(t.firstDrawAt - t.firstPaint),
      };
      console.log(JSON.stringify(row));
      await context.close();
    }
  }
} finally {
  await browser.close();
  await server.close();
}
