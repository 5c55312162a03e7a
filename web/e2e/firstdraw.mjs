// How soon the default scene starts drawing on a mid-range phone's stand-in:
// Chromium's mobile emulation (390×844, touch) with the CPU slowed 4× (CDP
// Emulation.setCPUThrottlingRate), from the page's first paint to its first
// frame with balloons; each run in a fresh context (a cold cache). After
// `npm run build`:
//
//   node e2e/firstdraw.mjs [--runs 3] [--rate 4]
//   --dist DIR       serves another build than dist/
//   --compare DIR    alternates each run between dist/ (or --dist) and the build in DIR, served
//                    side by side, so a change is measured against the build before it on the
//                    same machine at the same time (the shared machine's load moves in minutes)
//   --unslowed       also runs without the slowdown
//
// SwiftShader draws on this machine's CPU: the figures bound a phone's from
// above (a phone's GPU draws the frames), and say nothing of its frame rate.

import { launchChromium, TEST_PATH } from "./browser.mjs";
import { PHONE } from "./devices.mjs";
import { loadavg } from "node:os";
import { dirname, join, resolve } from "node:path";
import { fileURLToPath } from "node:url";
import { preview } from "vite";

const args = process.argv.slice(2);
const arg = (name, fallback) => {
  const i = args.indexOf(`--${name}`);
  return i >= 0 ? Number(args[i + 1]) : fallback;
};
const path = (name) => {
  const i = args.indexOf(`--${name}`);
  return i >= 0 ? resolve(args[i + 1]) : undefined;
};
const runs = arg("runs", 3);
const rate = arg("rate", 4);
const builds = [path("dist"), ...(path("compare") ? [path("compare")] : [])];
const slowdowns = args.includes("--unslowed") ? [rate, 1] : [rate];

const root = join(dirname(fileURLToPath(import.meta.url)), "..");
/** A preview server of the build in `dist` (undefined: dist/). */
async function serve(dist) {
  const vite = await preview({
    root,
    ...(dist ? { build: { outDir: dist } } : {}),
    logLevel: "warn",
    preview: { host: "127.0.0.1", port: 0, strictPort: true, open: false },
  });
  return { name: dist ?? join(root, "dist"), url: vite.resolvedUrls.local[0], close: () => vite.close() };
}
const servers = [];
for (const dist of builds) servers.push(await serve(dist));
const browser = await launchChromium();

/** A phone page of `server` on the default scene with the CPU slowed `slowdown`×, ready. */
async function phonePage(server, slowdown) {
  const context = await browser.newContext(PHONE);
  const page = await context.newPage();
  // The start of each animation frame: the first after the first frame with balloons is when that
  // frame had been shown (the page's thread waits until the GPU has drawn a frame, to composite it).
  await page.addInitScript(() => {
    const frames = (window.__frameStarts = []);
    const request = window.requestAnimationFrame.bind(window);
    window.requestAnimationFrame = (callback) =>
      request((t) => {
        if (frames.length < 1000) frames.push(performance.now());
        callback(t);
      });
  });
  const cdp = await context.newCDPSession(page);
  await cdp.send("Emulation.setCPUThrottlingRate", { rate: slowdown });
  await page.goto(server.url + TEST_PATH);
  await page.waitForFunction(() => window.__up?.ready(), null, { timeout: 300_000, polling: 100 });
  return { page, context };
}

// Times on the page's clock, ms: its first paint, the app's start (the bundle evaluated and the
// stage built, and how long the stage took), the balloon model's file in, the engine's first
// world and the model ready, the first frame with balloons (its render call returned, and the
// call's ms), that frame shown (the next animation frame's start), and both after the first paint.
const ms = (x) => (x === null || x === undefined ? null : Math.round(x));
try {
  for (const slowdown of slowdowns) {
    for (let r = 0; r < runs; r++) {
      for (const server of servers) {
        const load = loadavg()[0];
        const { page, context } = await phonePage(server, slowdown);
        const t = await page.evaluate(() => ({
          ...window.__up.firstDraw(),
          shownAt: window.__frameStarts.find((t) => t > window.__up.firstDraw().firstDrawAt) ?? null,
          modelFetch: performance.getEntriesByType("resource").find((e) => /\/assets\/balloon[^/]*\.(obj|bin)$/.test(e.name))?.responseEnd,
        }));
        const row = {
          build: server.name,
          slowdown,
          load: Math.round(load * 100) / 100,
          firstPaintMs: ms(t.firstPaint),
          startMs: ms(t.startAt),
          stageMs: ms(t.stageMs),
          modelFileMs: ms(t.modelFetch),
          engineMs: ms(t.engineAt),
          modelMs: ms(t.assetsAt),
          firstDrawMs: ms(t.firstDrawAt),
          firstRenderCallMs: ms(t.firstRenderMs),
          shownMs: ms(t.shownAt),
          afterPaintMs: ms(t.firstDrawAt - t.firstPaint),
          shownAfterPaintMs: t.shownAt === null ? null : ms(t.shownAt - t.firstPaint),
        };
        console.log(JSON.stringify(row));
        await context.close();
      }
    }
  }
} finally {
  await browser.close();
  for (const server of servers) await server.close();
}
