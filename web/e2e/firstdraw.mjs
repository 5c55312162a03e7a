// How soon the default scene starts drawing on a mid-range phone's stand-in:
// Chromium's mobile emulation (390×844, touch) with the CPU slowed 4× (CDP
// Emulation.setCPUThrottlingRate), from the page's first paint to its first
// frame with balloons; each run in a fresh context (a cold cache). After
// `npm run build`:
//
//   node e2e/firstdraw.mjs [--runs 3] [--rate 4]
//   node e2e/firstdraw.mjs --crowd        the balloons' share of a frame by count (full mesh), same profile
//
// SwiftShader draws on this machine's CPU: the figures bound a phone's from
// above (a phone's GPU draws the frames), and say nothing of its frame rate.

import { launchChromium, TEST_PATH, base64url } from "./browser.mjs";
import { PHONE } from "./devices.mjs";
import { serveDist } from "./serve.mjs";

const args = process.argv.slice(2);
const arg = (name, fallback) => {
  const i = args.indexOf(`--${name}`);
  return i >= 0 ? Number(args[i + 1]) : fallback;
};
const runs = arg("runs", 3);
const rate = arg("rate", 4);
const crowd = args.includes("--crowd");

const server = await serveDist();
const browser = await launchChromium();

/** A phone page with the CPU slowed `rate`×, opened at `hash`, ready. */
async function phonePage(hash, slowdown) {
  const context = await browser.newContext(PHONE);
  const page = await context.newPage();
  const cdp = await context.newCDPSession(page);
  await cdp.send("Emulation.setCPUThrottlingRate", { rate: slowdown });
  await page.goto(server.url + TEST_PATH + hash);
  await page.waitForFunction(() => window.__up?.ready(), null, { timeout: 300_000, polling: 100 });
  return { page, context };
}

try {
  if (!crowd) {
    const results = [];
    for (const slowdown of [rate, 1]) {
      for (let r = 0; r < runs; r++) {
        const { page, context } = await phonePage("", slowdown);
        const t = await page.evaluate(() => {
          const fetched = (re) => performance.getEntriesByType("resource").find((e) => re.test(e.name))?.responseEnd ?? null;
          return { ...window.__up.firstDraw(), wasmFetch: fetched(/up_wasm[^/]*\.wasm$/), modelFetch: fetched(/\.obj$/) };
        });
        const ms = (x) => (x === null ? null : Math.round(x));
        results.push({
          slowdown,
          firstPaintMs: ms(t.firstPaint),
          stageMs: ms(t.stageMs),
          wasmFetchMs: ms(t.wasmFetch),
          modelFetchMs: ms(t.modelFetch),
          engineMs: ms(t.engineAt),
          modelMs: ms(t.assetsAt),
          firstDrawMs: ms(t.firstDrawAt),
          firstRenderCallMs: ms(t.firstRenderMs),
          afterPaintMs: ms(t.firstDrawAt - t.firstPaint),
        });
        await context.close();
      }
    }
    for (const x of results) console.log(JSON.stringify(x));
  } else {
    // Full mesh at each count: ms per frame with the balloons, and without them (the room, its shadows).
    for (const n of [50, 150, 300, 500]) {
      const hash = `#scene=${base64url(JSON.stringify({ balloons: [{ count: n }] }))}`;
      const { page, context } = await phonePage(hash, rate);
      await page.evaluate(() => window.__up.holdDrawing(true));
      await page.evaluate(() => window.__up.setCrowdAbove(1e9));
      const full = await page.evaluate(() => window.__up.timeDraws(4));
      const room = await page.evaluate(() => window.__up.timeDraws(4, true));
      await page.evaluate(() => window.__up.setCrowdAbove(0));
      const light = await page.evaluate(() => window.__up.timeDraws(4));
      console.log(JSON.stringify({ balloons: n, fullMeshMs: +full.toFixed(1), crowdMeshMs: +light.toFixed(1), roomOnlyMs: +room.toFixed(1) }));
      await context.close();
    }
  }
} finally {
  await browser.close();
  await server.close();
}
