// Measures the page with many balloons in headless Chromium (WebGL through
// SwiftShader: the CPU draws, slowly), against the built app, once per thread
// count, on the same scene:
//
//   node e2e/measure.mjs [--balloons 10000] [--threads 1,2] [--steps 300] [--seconds 10]
//                        [--ribbons | --ribbons=0|1|both] [--rounds 1]
//                        [--pool here|beside[,…]] [--spin auto|0|1[,…]] [--setups POOL:SPIN,…]
//                        [--thread-times=0|1]
//                                                             (after `npm run build`)
//
// The scene: BALLOONS free balloons released from the floor of a square room
// wide enough to place them (the default scene's balloons and walls). With
// `--ribbons` (`--ribbons=1`) each hangs on the default scene's ribbon (1.5 m,
// read from the engine's `default_scene_json()`, the same definition the
// page's default scene has); `--ribbons=both` measures without and with
// ribbons in turn on each thread count, so that their ratio comes from one
// run on the same machine.
//
// Thread counts above one run the threaded module's pool as `--pool` and
// `--spin` say (sim/threadPool.ts: the physics worker one of the pool's
// threads or beside them; the pool's threads kept looking for work through a
// step, or only where they leave the page's drawing a core: auto; the page's
// defaults when not given); given several, each combination is measured in
// turn, or the pairs `--setups here:auto,beside:1` name. `--rounds N` repeats the whole sequence N
// times, so that the settings alternate on a machine whose load drifts.
//
// For each thread count T (and each ribbon setting) the page opens with `?threads=T`, then:
// 1. runs for `seconds` while an arrow key is pressed and the canvas clicked
//    every 400 ms: frame intervals, input delay, the main thread's frame work
//    (app/frameMeter.ts: controls, poses to instance matrices, HUD, plot; and
//    apart, the renderer.render call), and the steps per second the page
//    reaches (the real-time factor: simulated seconds per second);
// 2. the same with the balloons and their ribbons not drawn (`drawing_balloons`
//    holds step 1): SwiftShader takes seconds a frame at thousands of balloons
//    and the CPU from the worker, while the main thread's frame work is the
//    same — every pose still becomes an instance matrix each frame;
// 3. pauses and measures the frames alone for a few seconds (same input);
// 4. restarts the scene in the worker and times `steps` steps one by one
//    (sim/stepMeter.ts) while the page's frames do nothing (`holdDrawing`,
//    once SwiftShader has drawn those sent before): the physics ms per step by the engine's own timer over
//    the same window on every thread count, and the state hash after it,
//    which must be the same on every thread count. SwiftShader rasterises
//    on the same cores as the engine's threads, which a visitor's GPU does
//    not, so it is held off the window that times the engine;
// 5. the same window again with the page drawing (the balloons not drawn):
//    `physics_ms_while_drawing`, what this machine's page shows.
// Both windows also time each thread's part of each stage (unless
// `--thread-times=0`; two clock reads per task of a parallel pass):
// `physics_stage_threads_ms` (and `…_while_drawing`), per stage the ms a step
// each thread was busy, waited at a barrier and idled, the step's thread
// first, and the barriers and parallel passes it crossed; printed as tables.
// Ends with one JSON line: {"balloons", "steps", "ribbons": "off"|"on"|"both",
// "ribbon": the ribbon tied on (or null), "runs": [{"threads", "ribbons",
// "physics_ms": {median, mean, p95}, "physics_stages_ms": {stage: mean},
// "realtime_factor", "realtime_factor_wall", "frame_ms": {median, p95},
// "state_hash", "steps", "physics_ms_while_drawing", ...}], "modes": [{"ribbons",
// "speedup_mean": {"T": mean at 1 thread over mean at T}, "speedup_median",
// "speedup_mean_while_drawing", "hashes": {"T": hash}, "hashes_equal"}] (one
// a ribbon setting and pool setting, over the rounds: each ratio from the
// means of the rounds' means, and each round's ratio in "…_rounds"),
// "ribbon_cost" (with both: {"T": {"mean", "median"}: with over without}),
// "hashes_equal", ...}; a table of the same figures goes to standard error.
// Exits 1 when the hashes of one ribbon setting differ across thread counts.

import { base64url, launchChromium, TEST_PATH } from "./browser.mjs";
import { serveDist } from "./serve.mjs";
import { intArg } from "../scripts/cliArgs.mjs";
import { loadUpWasm } from "../sim-node/loadEngine.mjs";

/** `--ribbons` values: the ribbon settings measured, in the order they run on each thread count. */
const RIBBON_SETTINGS = { 0: [false], off: [false], 1: [true], on: [true], both: [false, true] };

/** The ribbon settings `--ribbons=VALUE` names (a bare `--ribbons`: on). */
function ribbonsArg(value) {
  const settings = Object.hasOwn(RIBBON_SETTINGS, value) ? RIBBON_SETTINGS[value] : undefined;
  if (!settings) throw new Error(`--ribbons: expected 0, 1 or both, found ${JSON.stringify(value)}`);
  return settings;
}

/** A comma list of `allowed` values. */
function listArg(name, text, allowed) {
  const values = text.split(",").map((v) => v.trim());
  for (const v of values) if (!allowed.includes(v)) throw new Error(`${name}: expected ${allowed.join(" or ")} (a comma list), found ${JSON.stringify(v)}`);
  return values;
}

function parseArgs(argv) {
  const opts = { balloons: 10000, threads: [1, 2], steps: 300, seconds: 10, ribbons: [false], rounds: 1, pool: [null], spin: [null], threadTimes: true };
  for (let i = 2; i < argv.length; i++) {
    const arg = argv[i];
    if (arg.startsWith("--ribbons=")) {
      opts.ribbons = ribbonsArg(arg.slice("--ribbons=".length));
      continue;
    }
    if (arg.startsWith("--thread-times=")) {
      const v = arg.slice("--thread-times=".length);
      if (v !== "0" && v !== "1") throw new Error(`--thread-times: expected 0 or 1, found ${JSON.stringify(v)}`);
      opts.threadTimes = v === "1";
      continue;
    }
    const value = () => {
      if (i + 1 >= argv.length) throw new Error(`${arg}: expected a value`);
      return argv[++i];
    };
    switch (arg) {
      case "--balloons": opts.balloons = intArg(arg, value(), 1, 50000); break;
      case "--threads": {
        const list = value();
        opts.threads = list.split(",").map((t) => intArg("--threads (a comma list)", t.trim(), 1, 256));
        break;
      }
      case "--steps": opts.steps = intArg(arg, value(), 1, 20000); break;
      case "--seconds": opts.seconds = intArg(arg, value(), 1, 600); break;
      case "--ribbons": opts.ribbons = RIBBON_SETTINGS.on; break;
      case "--rounds": opts.rounds = intArg(arg, value(), 1, 100); break;
      case "--pool": opts.pool = listArg(arg, value(), ["here", "beside"]); break;
      case "--spin": opts.spin = listArg(arg, value(), ["auto", "0", "1"]); break;
      case "--setups":
        opts.setups = value().split(",").map((pair) => {
          const [pool, spin] = pair.split(":");
          listArg("--setups (POOL:SPIN pairs)", pool, ["here", "beside"]);
          listArg("--setups (POOL:SPIN pairs)", spin ?? "", ["auto", "0", "1"]);
          return { pool, spin };
        });
        break;
      default: throw new Error(`unknown argument ${JSON.stringify(arg)} (node e2e/measure.mjs [--balloons N] [--threads 1,2] [--steps S] [--seconds S] [--ribbons | --ribbons=0|1|both] [--rounds N] [--pool here|beside[,…]] [--spin auto|0|1[,…]] [--setups POOL:SPIN,…] [--thread-times=0|1])`);
    }
  }
  return opts;
}

const viewport = { width: 960, height: 600 };
const t0 = Date.now();
/** Progress on standard error (standard output ends with the one JSON line). */
const log = (text) => console.error(`measure.mjs [${Math.round((Date.now() - t0) / 1000)} s]: ${text}`);
const round = (x, digits = 1) => (x === null || x === undefined ? null : Math.round(x * 10 ** digits) / 10 ** digits);

/** Nearest-rank quantile, as the benchmarks take it. */
function quantile(sorted, q) {
  const rank = Math.ceil(Math.min(Math.max(q, 0), 1) * sorted.length);
  return sorted[Math.min(Math.max(rank, 1), sorted.length) - 1];
}

const summary = (xs, digits = 1) => {
  const s = [...xs].sort((a, b) => a - b);
  if (!s.length) return { n: 0, median: null, mean: null, p95: null, max: null };
  return {
    n: s.length,
    median: round(quantile(s, 0.5), digits),
    mean: round(s.reduce((a, b) => a + b, 0) / s.length, digits),
    p95: round(quantile(s, 0.95), digits),
    max: round(s[s.length - 1], digits),
  };
};

/** Installed in the page: a frame-interval recorder and input-event listeners (capture phase, first to run). */
function instrument() {
  const m = { raf: [], input: [], toFrame: [], pending: [] };
  window.__measure = m;
  const loop = (t) => {
    m.raf.push(t);
    for (const stamp of m.pending) m.toFrame.push(t - stamp);
    m.pending.length = 0;
    requestAnimationFrame(loop);
  };
  requestAnimationFrame(loop);
  const onInput = (e) => {
    m.input.push(performance.now() - e.timeStamp);
    m.pending.push(e.timeStamp);
  };
  window.addEventListener("keydown", onInput, true);
  window.addEventListener("pointerdown", onInput, true);
}

/** Runs for `ms`, pressing ArrowLeft and clicking the floor in turn every 400 ms; samples the worker's stats. */
async function phase(page, ms) {
  await page.evaluate(() => {
    const m = window.__measure;
    m.raf.length = 0;
    m.input.length = 0;
    m.toFrame.length = 0;
    m.start = performance.now();
    window.__up.resetFrameMeter();
  });
  const stats = [];
  const end = Date.now() + ms;
  let turn = 0;
  while (Date.now() < end) {
    if (turn++ % 2 === 0) await page.keyboard.press("ArrowLeft", { delay: 30 });
    else await page.mouse.click(viewport.width * 0.3, viewport.height * 0.9);
    await page.waitForTimeout(400);
    const s = await page.evaluate(() => window.__up.stats());
    if (s) stats.push(s);
  }
  const got = await page.evaluate(() => {
    const m = window.__measure;
    return {
      raf: m.raf.slice(1).map((t, i) => t - m.raf[i]),
      input: m.input.slice(),
      toFrame: m.toFrame.slice(),
      meter: window.__up.frameMeter(),
      elapsed: (performance.now() - m.start) / 1000,
    };
  });
  const totals = stats.map((s) => s.stats.stages.find(([name]) => name === "total")?.[1] ?? 0).filter((t) => t > 0);
  // The worker's own count (the frames' step counts arrive late while frames are slow).
  const rates = stats.map((s) => s.stepsPerSecond).filter((r) => r > 0);
  const stepsPerSecond = rates.length ? rates.reduce((a, b) => a + b, 0) / rates.length : 0;
  const part = (p) => (p ? { median: round(p.median, 2), p95: round(p.p95, 2), mean: round(p.mean, 2), max: round(p.max, 2) } : null);
  return {
    frame_ms: part(got.meter.work),
    render_call_ms: part(got.meter.render),
    frames: got.meter.n,
    fps: round(got.meter.n / got.elapsed),
    raf_interval_ms: summary(got.raf),
    input_delay_ms: summary(got.input),
    input_to_frame_ms: summary(got.toFrame),
    steps_per_s: round(stepsPerSecond),
    realtime_factor: round(stepsPerSecond / 60, 2),
    // The worker's stats, each the mean over the steps since the last (≈ 250 ms).
    stats_ms_per_step: summary(totals),
  };
}

/**
 * Holds the page's drawing and waits until SwiftShader has drawn every frame
 * sent before (seconds each at thousands of balloons, on the CPU, also after
 * the render call returned): the frames then come at the display's rate, 30
 * in a row under 40 ms apart (at most `timeoutMs`).
 */
async function settleDrawing(page, timeoutMs = 300_000) {
  await page.evaluate(() => window.__up.holdDrawing(true));
  await page.evaluate(() => window.__up.finishDrawing());
  const settled = await page.evaluate(
    (timeout) =>
      new Promise((resolve) => {
        const start = performance.now();
        let last = start;
        let quick = 0;
        const tick = (t) => {
          quick = t - last < 40 ? quick + 1 : 0;
          last = t;
          if (quick >= 30) resolve(true);
          else if (t - start > timeout) resolve(false);
          else requestAnimationFrame(tick);
        };
        requestAnimationFrame(tick);
      }),
    timeoutMs,
  );
  if (!settled) throw new Error(`the page's frames did not settle within ${timeoutMs / 1000} s of holding its drawing`);
}

/** A run's name in the log and the tables. */
function runLabel(threads, ribbons, setup) {
  const pool = threads > 1 ? `, pool ${setup.pool ?? "default"}, spin ${setup.spin ?? "default"}` : "";
  return `${threads} thread(s), ${ribbons ? "with" : "without"} ribbons${pool}`;
}

/** The window's per-thread figures by stage (stepMeter's `threadStages`), rounded: {stage: {wall, barriers, passes, busy, barrier, idle}}. */
function stageThreads(rows) {
  const ms = (v) => v.map((x) => round(x, 2));
  return Object.fromEntries(
    (rows ?? []).map((r) => [r.stage, { wall: round(r.wall_ms, 2), barriers: round(r.barriers, 1), passes: round(r.passes, 1), busy: ms(r.busy_ms), barrier: ms(r.barrier_ms), idle: ms(r.idle_ms) }]),
  );
}

/** Measures the page on `threads` threads, each balloon on a ribbon where `ribbons`, its pool as `setup` says. */
async function measureThreads(browser, url, opts, threads, ribbons, setup, dt) {
  const page = await browser.newPage({ viewport });
  const label = runLabel(threads, ribbons, setup);
  const errors = [];
  page.on("pageerror", (e) => errors.push(e.message));
  try {
    const started = Date.now();
    await page.goto(url(threads, ribbons, setup));
    await page.waitForFunction(() => window.__up?.ready(), null, { timeout: 900_000, polling: 500 });
    const loadSeconds = (Date.now() - started) / 1000;
    const inPage = await page.evaluate(() => ({
      count: window.__up.balloonCount(),
      ribbons: window.__up.ribbonCount(),
      // Present where the page runs a thread pool.
      threads: typeof window.__up.threads === "function" ? window.__up.threads() : null,
      isolated: typeof window.__up.isolated === "function" ? window.__up.isolated() : window.crossOriginIsolated,
    }));
    // The page falls back to its default scene where the engine refuses the link's: measure only the scene asked for.
    const wantRibbons = ribbons ? opts.balloons : 0;
    if (inPage.count !== opts.balloons || inPage.ribbons !== wantRibbons) {
      throw new Error(`the page runs ${inPage.count} balloons and ${inPage.ribbons} ribbons, expected ${opts.balloons} and ${wantRibbons}`);
    }
    await page.evaluate(instrument);
    const drawn = await phase(page, opts.seconds * 1000);
    log(`${label}: loaded in ${round(loadSeconds)} s; ran ${opts.seconds} s drawing the balloons (${drawn.frames} frames)`);
    // SwiftShader draws thousands of balloons in seconds a frame on the CPU, which
    // leaves few frames to measure and takes the cores from the worker: from here
    // the balloons are not drawn, while the frame's work (their poses to instance
    // matrices included) goes on every frame.
    await page.evaluate(() => window.__up.drawBalloons(false));
    const running = await phase(page, opts.seconds * 1000);
    log(`${label}: ran ${opts.seconds} s not drawing them (${running.frames} frames)`);
    await page.keyboard.press(" ");
    // Seconds at 10,000 balloons: SwiftShader's frames hold the main thread's key handling back.
    await page.waitForFunction(() => window.__up.paused(), null, { timeout: 300_000, polling: 200 });
    await page.waitForTimeout(500);
    const paused = await phase(page, Math.min(5, opts.seconds) * 1000);
    log(`${label}: drawing alone measured (${paused.frames} frames); timing ${opts.steps} steps`);
    // The worker restarts the scene and steps the window; the page's frames
    // held (they do nothing), then the same window with the page drawing.
    const timeWindow = async (held) => {
      if (held) await settleDrawing(page);
      else await page.evaluate(() => window.__up.holdDrawing(false));
      return page.evaluate(([steps, threadTimes]) => window.__up.measureSteps(steps, threadTimes), [opts.steps, opts.threadTimes]);
    };
    const window_ = await timeWindow(true);
    const physics = summary(window_.engineMs, 2);
    log(`${label}: physics mean ${physics.mean} ms per step, drawing held; the window again, drawing`);
    const whileDrawing = await timeWindow(false);
    const physicsWhileDrawing = summary(whileDrawing.engineMs, 2);
    if (whileDrawing.stateHash !== window_.stateHash) {
      throw new Error(`the window ended on ${window_.stateHash} drawing held and on ${whileDrawing.stateHash} drawing`);
    }
    const dtMs = dt * 1000;
    const wall = summary(window_.wallMs, 2);
    return {
      threads,
      ribbons,
      pool: setup.pool,
      spin: setup.spin,
      ribbons_in_page: inPage.ribbons,
      threads_in_page: inPage.threads,
      isolated: inPage.isolated,
      balloons: inPage.count,
      physics_ms: { median: physics.median, mean: physics.mean, p95: physics.p95, max: physics.max },
      physics_wall_ms: wall,
      // The engine's stages over the same window: each one's mean ms per step (which ones scale).
      physics_stages_ms: Object.fromEntries(window_.stageMeanMs.map(([name, ms]) => [name, round(ms, 2)])),
      // Each thread's part of each stage over the same window (the step's thread first), and while drawing.
      physics_stage_threads_ms: stageThreads(window_.threadStages),
      physics_stage_threads_ms_while_drawing: stageThreads(whileDrawing.threadStages),
      // The same window while the page draws (the balloons not drawn): SwiftShader on the same cores.
      physics_ms_while_drawing: { median: physicsWhileDrawing.median, mean: physicsWhileDrawing.mean, p95: physicsWhileDrawing.p95, max: physicsWhileDrawing.max },
      // Simulated seconds per second at the window's mean (1: real time), and what the page
      // reached while running (at most 1: the worker steps in real time or slower).
      realtime_factor: round(dtMs / physics.mean, 3),
      // The same by the worker's clock around each step call (simulated seconds per wall second while stepping).
      realtime_factor_wall: round(dtMs / wall.mean, 3),
      page_realtime_factor: running.realtime_factor,
      // The main thread's frame work (the render call apart) while the worker steps, balloons not drawn.
      frame_ms: running.frame_ms,
      render_call_ms: running.render_call_ms,
      raf_interval_ms: running.raf_interval_ms,
      input_delay_ms: running.input_delay_ms,
      input_to_frame_ms: running.input_to_frame_ms,
      fps: running.fps,
      // The same while SwiftShader draws the balloons (few frames at thousands).
      drawing_balloons: {
        frame_ms: drawn.frame_ms,
        render_call_ms: drawn.render_call_ms,
        raf_interval_ms: drawn.raf_interval_ms,
        input_delay_ms: drawn.input_delay_ms,
        fps: drawn.fps,
        realtime_factor: drawn.realtime_factor,
      },
      paused_not_drawing_balloons: { frame_ms: paused.frame_ms, render_call_ms: paused.render_call_ms, raf_interval_ms: paused.raf_interval_ms, fps: paused.fps },
      state_hash: window_.stateHash,
      steps: window_.steps,
      awake_at_end: window_.awake,
      contacts_at_end: window_.contacts,
      load_to_first_frames_s: round(loadSeconds),
      page_errors: errors,
    };
  } finally {
    await page.close();
  }
}

/** The default scene's ribbon and step, from the engine the page runs (its single-threaded module, in Node). */
async function engineDefaults() {
  const { glue } = await loadUpWasm({ threads: 1 });
  const defaults = JSON.parse(glue.default_scene_json());
  const ribbon = defaults.balloons?.find((g) => g.ribbon)?.ribbon;
  if (!ribbon) throw new Error("the engine's default scene has no ribbon to tie on");
  return { ribbon, dt: defaults.sim.dt };
}

/** A pool setting's name: "pool=here spin=0" ("default" where the page's default is measured). */
const setupName = (setup) => `pool=${setup.pool ?? "default"} spin=${setup.spin ?? "default"}`;

const mean = (xs) => (xs.length ? xs.reduce((a, b) => a + b, 0) / xs.length : null);

/**
 * The figures within one ribbon setting and one pool setting, over the
 * rounds: speed-ups over one thread (the rounds' means of each, then their
 * ratio; and each round's own ratio) and the hashes by thread count.
 */
function modeSummary(measured, ribbons, setup) {
  const name = setupName(setup);
  const base = measured.filter((r) => r.ribbons === ribbons && r.threads === 1);
  const runs = measured.filter((r) => r.ribbons === ribbons && r.threads > 1 && setupName(r) === name);
  const counts = [...new Set(runs.map((r) => r.threads))];
  // No 1-thread run to compare with: no ratio (rather than a 0).
  const ratio = (key, field = "physics_ms") =>
    base.length === 0
      ? null
      : Object.fromEntries(counts.map((t) => [String(t), round(mean(base.map((r) => r[field][key])) / mean(runs.filter((r) => r.threads === t).map((r) => r[field][key])), 2)]));
  const perRound = (key, field = "physics_ms") =>
    Object.fromEntries(
      counts.map((t) => [
        String(t),
        runs
          .filter((r) => r.threads === t)
          .map((r) => {
            const b = base.find((x) => x.round === r.round);
            return b ? round(b[field][key] / r[field][key], 2) : null;
          }),
      ]),
    );
  const all = [...base, ...runs];
  return {
    ribbons,
    pool: name,
    rounds: Math.max(0, ...all.map((r) => r.round + 1)),
    speedup_mean: ratio("mean"),
    speedup_median: ratio("median"),
    speedup_mean_rounds: perRound("mean"),
    // The same by the worker's clock around each step call (the engine's time, and any wait for the pool's workers).
    speedup_wall_mean: ratio("mean", "physics_wall_ms"),
    // While SwiftShader draws the page on the same cores.
    speedup_mean_while_drawing: ratio("mean", "physics_ms_while_drawing"),
    speedup_median_while_drawing: ratio("median", "physics_ms_while_drawing"),
    speedup_mean_while_drawing_rounds: perRound("mean", "physics_ms_while_drawing"),
    hashes: Object.fromEntries(all.map((r) => [String(r.threads), r.state_hash])),
    hashes_equal: all.every((r) => r.state_hash === all[0].state_hash),
  };
}

/** With and without ribbons on each thread count and pool setting: the step with ribbons over the step without (means of the rounds). */
function ribbonCost(measured) {
  const cost = {};
  for (const key of new Set(measured.filter((r) => r.ribbons).map((r) => `${r.threads} ${setupName(r)}`))) {
    const alike = (r) => `${r.threads} ${setupName(r)}` === key;
    const on = measured.filter((r) => r.ribbons && alike(r));
    const off = measured.filter((r) => !r.ribbons && alike(r));
    if (!off.length) continue;
    const over = (k, field = "physics_ms") => round(mean(on.map((r) => r[field][k])) / mean(off.map((r) => r[field][k])), 2);
    cost[on[0].threads > 1 ? key : "1"] = { mean: over("mean"), median: over("median"), wall_mean: over("mean", "physics_wall_ms"), while_drawing_mean: over("mean", "physics_ms_while_drawing") };
  }
  return cost;
}

/** One window's per-thread figures as a table, up-bench's `--thread-times` layout: stages over 1 % of the step, and the total. */
function threadTable(stages) {
  const rows = Object.entries(stages);
  if (!rows.length) return "";
  const total = stages.total?.wall ?? 0;
  const threads = rows[0][1].busy.length;
  const head = ["stage, ms/step", "wall", "barriers", "passes", ...Array.from({ length: threads }, (_, t) => `${t === 0 ? "step's" : `t${t}`} busy/barrier/idle`)];
  const body = rows
    .filter(([name, r]) => name === "total" || r.wall >= 0.01 * total)
    .map(([name, r]) => [name, r.wall.toFixed(2), r.barriers.toFixed(1), r.passes.toFixed(1), ...r.busy.map((b, t) => `${b.toFixed(2)}/${r.barrier[t].toFixed(2)}/${r.idle[t].toFixed(2)}`)]);
  const all = [head, ...body];
  const widths = head.map((_, c) => Math.max(...all.map((row) => (row[c] ?? "").length)));
  return all.map((row) => row.map((cell, c) => (c === 0 ? cell.padEnd(widths[c]) : cell.padStart(widths[c]))).join("  ")).join("\n");
}

/** The runs as a table on standard error (standard output keeps the one JSON line). */
function printTable(runs, modes, cost) {
  const rows = [["round", "ribbons", "threads", "pool", "mean ms", "median ms", "p95 ms", "wall mean ms", "drawing mean ms", "drawing median ms", "realtime", "hash"]];
  for (const r of runs) {
    const pool = r.threads > 1 ? setupName(r) : "single module";
    if (r.error) rows.push([String(r.round + 1), r.ribbons ? "on" : "off", String(r.threads), pool, `failed: ${r.error}`]);
    else
      rows.push([
        String(r.round + 1),
        r.ribbons ? "on" : "off",
        String(r.threads),
        pool,
        ...[r.physics_ms.mean, r.physics_ms.median, r.physics_ms.p95, r.physics_wall_ms.mean, r.physics_ms_while_drawing.mean, r.physics_ms_while_drawing.median].map(String),
        `${r.realtime_factor}×`,
        r.state_hash,
      ]);
  }
  const widths = rows[0].map((_, c) => Math.max(...rows.map((row) => (row[c] ?? "").length)));
  for (const row of rows) console.error(row.map((cell, c) => (cell ?? "").padEnd(widths[c])).join("  ").trimEnd());
  for (const m of modes) {
    // No 1-thread run beside them (`--threads 2`): no ratio to print.
    for (const [t, s] of Object.entries(m.speedup_mean ?? {})) {
      console.error(
        `${t} threads over 1, ${m.ribbons ? "with" : "without"} ribbons, ${m.pool}: ${s}× by the mean (rounds ${m.speedup_mean_rounds[t].join(", ")}), ${m.speedup_median[t]}× by the median; while drawing ${m.speedup_mean_while_drawing[t]}× by the mean (rounds ${m.speedup_mean_while_drawing_rounds[t].join(", ")}), ${m.speedup_median_while_drawing[t]}× by the median`,
      );
    }
  }
  for (const [key, c] of Object.entries(cost)) {
    console.error(`ribbons' cost on ${key} thread(s): ${c.mean}× by the mean, ${c.median}× by the median`);
  }
  for (const r of runs.filter((r) => !r.error)) {
    const name = `round ${r.round + 1}, ${runLabel(r.threads, r.ribbons, r)}`;
    // The stages that take time (the others round to 0).
    const list = Object.entries(r.physics_stages_ms).filter(([, ms]) => ms > 0).map(([stage, ms]) => `${stage} ${ms}`).join(", ");
    console.error(`stages, ms a step (${name}): ${list}`);
    if (Object.keys(r.physics_stage_threads_ms).length) {
      console.error(`each thread's part of each stage, drawing held (${name}):\n${threadTable(r.physics_stage_threads_ms)}`);
      console.error(`the same while drawing:\n${threadTable(r.physics_stage_threads_ms_while_drawing)}`);
    }
  }
}

const opts = parseArgs(process.argv);
/** A room large enough to place the balloons without overlap (about 40 per m² of floor, stacked). */
const side = Math.max(6, Math.ceil(Math.sqrt(opts.balloons / 30)));
const { ribbon, dt } = await engineDefaults();
/** The scene measured, without or with the default scene's ribbon on every balloon. */
const sceneOf = (ribbons) => ({ room: { width: side, depth: side }, balloons: [ribbons ? { count: opts.balloons, ribbon } : { count: opts.balloons }] });
const settingName = opts.ribbons.length > 1 ? "both" : opts.ribbons[0] ? "on" : "off";
/** The pool settings measured on more than one thread (null: the page's default). */
const setups = opts.setups ?? opts.pool.flatMap((pool) => opts.spin.map((spin) => ({ pool, spin })));
const server = await serveDist();
const browser = await launchChromium();
let failed = false;
try {
  const url = (threads, ribbons, setup) => {
    const pool = threads > 1 ? `${setup.pool ? `&pool=${setup.pool}` : ""}${setup.spin ? `&spin=${setup.spin}` : ""}` : "";
    return `${server.url}${TEST_PATH}&threads=${threads}${pool}#scene=${base64url(JSON.stringify(sceneOf(ribbons)))}`;
  };
  const runs = [];
  // Without and with ribbons in turn on each thread count and pool setting, round after round:
  // the machine's load drifts alike over all of them.
  for (let round_ = 0; round_ < opts.rounds; round_++) {
    for (const threads of opts.threads) {
      for (const ribbons of opts.ribbons) {
        // One thread runs the single-threaded module: no pool to set.
        for (const setup of threads > 1 ? setups : [{ pool: null, spin: null }]) {
          const label = `round ${round_ + 1}, ${runLabel(threads, ribbons, setup)}`;
          try {
            runs.push({ round: round_, ...(await measureThreads(browser, url, opts, threads, ribbons, setup, dt)) });
          } catch (e) {
            // The other runs are still measured; the run fails at the end.
            log(`${label} failed: ${e.message}`);
            runs.push({ round: round_, threads, ribbons, pool: setup.pool, spin: setup.spin, error: e.message });
            continue;
          }
          log(`${label}: ${JSON.stringify(runs.at(-1))}`);
          log(`${label}: physics mean ${runs.at(-1).physics_ms.mean} ms per step, frame work median ${runs.at(-1).frame_ms?.median} ms`);
        }
      }
    }
  }
  const measured = runs.filter((r) => !r.error);
  const modes = opts.ribbons.flatMap((ribbons) => setups.map((setup) => modeSummary(measured, ribbons, setup)));
  const hashesEqual = opts.ribbons.every((ribbons) => {
    const alike = measured.filter((r) => r.ribbons === ribbons);
    return alike.every((r) => r.state_hash === alike[0].state_hash);
  });
  const cost = ribbonCost(measured);
  failed = !hashesEqual || measured.length < runs.length;
  printTable(runs, modes, cost);
  console.log(
    JSON.stringify({
      balloons: measured[0]?.balloons ?? opts.balloons,
      room_m: [side, side],
      steps: opts.steps,
      rounds: opts.rounds,
      ribbons: settingName,
      ribbon: opts.ribbons.includes(true) ? ribbon : null,
      dt,
      runs,
      modes,
      ribbon_cost: cost,
      hashes_equal: hashesEqual,
      viewport,
      chromium: browser.version(),
      renderer: "SwiftShader (CPU)",
    }),
  );
  for (const m of modes.filter((m) => !m.hashes_equal)) {
    console.error(`measure.mjs: the state hashes ${m.ribbons ? "with" : "without"} ribbons differ across thread counts (${m.pool}): ${Object.entries(m.hashes).map(([t, h]) => `${t}: ${h}`).join(", ")}`);
  }
} finally {
  await browser.close();
  await server.close();
}
if (failed) process.exit(1);
