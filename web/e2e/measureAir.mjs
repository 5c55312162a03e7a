// What "show air" costs the page's frame: the main thread's frame work (the
// page's frame meter, app/frameMeter.ts: everything before the render call)
// and the render call, with the motes shown and not, at BALLOONS balloons
// (5,000) and one sweeping fan placed with the fan tool, in headless Chromium
// against the built app:
//
//   node e2e/measureAir.mjs [--balloons 5000] [--seconds 8] [--rounds 3]     (after `npm run build`)
//
// The scene is e2e/measure.mjs's (the balloons released from the floor of a
// room wide enough to hold them). As there, the balloons and ribbons are not
// drawn while measuring (SwiftShader takes seconds to draw thousands, on the
// CPU), while every pose still becomes an instance matrix each frame. Windows
// of `seconds` alternate off, on, off, on, … (`rounds` of each) so that the
// machine's load drifts alike over both; one JSON line at the end: each
// window's medians, and by mode the median of the windows' medians and the
// difference on − off.

import { base64url, launchChromium, TEST_PATH } from "./browser.mjs";
import { serveDist } from "./serve.mjs";
import { intArg } from "../scripts/cliArgs.mjs";

function parseArgs(argv) {
  const opts = { balloons: 5000, seconds: 8, rounds: 3 };
  for (let i = 2; i < argv.length; i++) {
    const arg = argv[i];
    const value = () => {
      if (i + 1 >= argv.length) throw new Error(`${arg}: expected a value`);
      return argv[++i];
    };
    switch (arg) {
      case "--balloons": opts.balloons = intArg(arg, value(), 1, 50000); break;
      case "--seconds": opts.seconds = intArg(arg, value(), 1, 600); break;
      case "--rounds": opts.rounds = intArg(arg, value(), 1, 20); break;
      default: throw new Error(`unknown argument ${JSON.stringify(arg)} (node e2e/measureAir.mjs [--balloons N] [--seconds S] [--rounds R])`);
    }
  }
  return opts;
}

const viewport = { width: 960, height: 600 };
const t0 = Date.now();
const log = (text) => console.error(`measureAir.mjs [${Math.round((Date.now() - t0) / 1000)} s]: ${text}`);
const round = (x, digits = 3) => (x === null || x === undefined ? null : Math.round(x * 10 ** digits) / 10 ** digits);
const median = (xs) => {
  const s = [...xs].sort((a, b) => a - b);
  return s.length ? s[Math.ceil(0.5 * s.length) - 1] : null;
};

const opts = parseArgs(process.argv);
const side = Math.max(6, Math.ceil(Math.sqrt(opts.balloons / 30)));
const scene = { room: { width: side, depth: side }, balloons: [{ count: opts.balloons }] };
const server = await serveDist();
const browser = await launchChromium();
try {
  const page = await browser.newPage({ viewport });
  const errors = [];
  page.on("pageerror", (e) => errors.push(e.message));
  await page.goto(`${server.url}${TEST_PATH}#scene=${base64url(JSON.stringify(scene))}`);
  await page.waitForFunction(() => window.__up?.ready(), null, { timeout: 900_000, polling: 500 });
  log(`loaded ${await page.evaluate(() => window.__up.balloonCount())} balloons`);
  await page.evaluate(() => window.__up.drawBalloons(false));
  // One sweeping fan near a wall, aimed across the room, placed as a user does.
  await page.locator('[data-key="fanSweep"] input').check();
  await page.locator('[data-key="fanTool"] input').check();
  const at = await page.evaluate((z) => window.__up.project(0, 0, z), side / 2 - 1);
  await page.mouse.click(at.x, at.y);
  await page.waitForFunction(() => window.__up.air().sources.length === 1, null, { timeout: 300_000 });
  await page.locator('[data-key="fanTool"] input').uncheck();
  const showAir = page.locator('[data-key="showAir"] input');
  const windows = [];
  for (let r = 0; r < opts.rounds; r++) {
    for (const on of [false, true]) {
      if (on) await showAir.check();
      else await showAir.uncheck();
      // A second for the first field to arrive and the motes to fill the jet.
      await page.waitForTimeout(1500);
      await page.evaluate(() => window.__up.resetFrameMeter());
      await page.waitForTimeout(opts.seconds * 1000);
      const got = await page.evaluate(() => ({ meter: window.__up.frameMeter(), air: window.__up.air() }));
      const w = {
        show_air: on,
        frames: got.meter.n,
        work_median_ms: round(got.meter.work?.median),
        render_median_ms: round(got.meter.render?.median),
        work_p95_ms: round(got.meter.work?.p95),
        motes_visible: got.air.motesVisible,
      };
      windows.push(w);
      log(JSON.stringify(w));
    }
  }
  const byMode = (on) => {
    const ws = windows.filter((w) => w.show_air === on);
    return { work_median_ms: round(median(ws.map((w) => w.work_median_ms))), render_median_ms: round(median(ws.map((w) => w.render_median_ms))) };
  };
  const off = byMode(false);
  const on = byMode(true);
  console.log(
    JSON.stringify({
      balloons: opts.balloons,
      room_m: [side, side],
      seconds: opts.seconds,
      windows,
      off,
      on,
      cost_ms: {
        work: round(on.work_median_ms - off.work_median_ms),
        render: round(on.render_median_ms - off.render_median_ms),
        work_and_render: round(on.work_median_ms + on.render_median_ms - off.work_median_ms - off.render_median_ms),
      },
      page_errors: errors,
      viewport,
      chromium: browser.version(),
    }),
  );
} finally {
  await browser.close();
  await server.close();
}
