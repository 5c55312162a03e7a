// Measures the claim "with 5,000 balloons the page keeps drawing and answering
// input while the simulation runs", in headless Chromium (WebGL through
// SwiftShader: the CPU draws, slowly), against the built app:
//
//   node e2e/measure.mjs [balloons=5000] [seconds=10]     (after `npm run build`)
//
// Loads a scene link with that many balloons, then for `seconds` presses an
// arrow key and clicks the canvas every 400 ms while the worker simulates,
// then pauses the simulation and measures again (drawing alone, same input). Prints one
// JSON line:
// - frame_ms: main-thread requestAnimationFrame intervals (median, p95, max);
// - input_delay_ms: from an input event's timestamp to its handler running
//   (how long the main thread kept it waiting);
// - input_to_frame_ms: from the event to the start of the next frame;
// - render_call_ms: main-thread time inside renderer.render per frame (the
//   rest of the frame is SwiftShader rasterising in the GPU process);
// - physics: the worker's engine ms per step by stage, steps per second, and
//   the real-time factor (simulated seconds per second; 1 is real time).

import { base64url, launchChromium, TEST_PATH } from "./browser.mjs";
import { serveDist } from "./serve.mjs";

const balloons = Number(process.argv[2] ?? 5000);
const seconds = Number(process.argv[3] ?? 10);
const viewport = { width: 960, height: 600 };
/** A room large enough to place the balloons without overlap (about 40 per m² of floor, stacked). */
const side = Math.max(6, Math.ceil(Math.sqrt(balloons / 30)));
const scene = { room: { width: side, depth: side }, balloons: [{ count: balloons }] };

const summary = (xs) => {
  const s = [...xs].sort((a, b) => a - b);
  const at = (q) => (s.length ? s[Math.min(s.length - 1, Math.floor(q * s.length))] : null);
  const round = (x) => (x === null ? null : Math.round(x * 10) / 10);
  return { n: s.length, median: round(at(0.5)), p95: round(at(0.95)), max: round(s.length ? s[s.length - 1] : null) };
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
async function phase(page, ms, withInput) {
  await page.evaluate(() => {
    const m = window.__measure;
    m.raf.length = 0;
    m.input.length = 0;
    m.toFrame.length = 0;
    m.framesBefore = window.__up.frames();
    m.stepsBefore = window.__up.steps();
    m.start = performance.now();
  });
  const stats = [];
  const end = Date.now() + ms;
  let turn = 0;
  while (Date.now() < end) {
    if (withInput) {
      if (turn++ % 2 === 0) await page.keyboard.press("ArrowLeft", { delay: 30 });
      else await page.mouse.click(viewport.width * 0.3, viewport.height * 0.9);
    }
    await page.waitForTimeout(400);
    const s = await page.evaluate(() => window.__up.stats());
    if (s) stats.push(s);
  }
  const page_ = await page.evaluate(() => {
    const m = window.__measure;
    const frames = window.__up.frames();
    const raf = m.raf.slice(1).map((t, i) => t - m.raf[i]);
    const drawn = frames.drawn - m.framesBefore.drawn;
    return {
      raf,
      input: m.input.slice(),
      toFrame: m.toFrame.slice(),
      drawn,
      renderMsPerFrame: drawn > 0 ? (frames.renderMs - m.framesBefore.renderMs) / drawn : null,
      steps: window.__up.steps() - m.stepsBefore,
      elapsed: (performance.now() - m.start) / 1000,
    };
  });
  const totals = stats.map((s) => s.stats.stages.find(([name]) => name === "total")?.[1] ?? 0).filter((t) => t > 0);
  const stageNames = stats.length ? stats[stats.length - 1].stats.stages.map(([name]) => name) : [];
  const stages = Object.fromEntries(
    stageNames.map((name) => {
      const xs = stats.map((s) => s.stats.stages.find(([n]) => n === name)?.[1] ?? 0);
      return [name, Math.round((xs.reduce((a, b) => a + b, 0) / Math.max(1, xs.length)) * 100) / 100];
    }),
  );
  const stepsPerSecond = page_.steps / page_.elapsed;
  return {
    frame_ms: summary(page_.raf),
    fps: Math.round((page_.drawn / page_.elapsed) * 10) / 10,
    render_call_ms: page_.renderMsPerFrame === null ? null : Math.round(page_.renderMsPerFrame * 10) / 10,
    ...(withInput ? { input_delay_ms: summary(page_.input), input_to_frame_ms: summary(page_.toFrame) } : {}),
    physics: {
      ms_per_step: summary(totals),
      stages_ms_mean: stages,
      steps_per_s: Math.round(stepsPerSecond * 10) / 10,
      realtime_factor: Math.round(stepsPerSecond * (1 / 60) * 100) / 100,
      contacts: stats.length ? stats[stats.length - 1].stats.contacts : null,
      awake: stats.length ? stats[stats.length - 1].stats.awake : null,
    },
  };
}

const server = await serveDist();
const browser = await launchChromium();
try {
  const page = await browser.newPage({ viewport });
  const errors = [];
  page.on("pageerror", (e) => errors.push(e.message));
  const started = Date.now();
  await page.goto(`${server.url}${TEST_PATH}#scene=${base64url(JSON.stringify(scene))}`);
  await page.waitForFunction(() => window.__up?.ready(), null, { timeout: 180_000, polling: 500 });
  const loadSeconds = (Date.now() - started) / 1000;
  const count = await page.evaluate(() => window.__up.balloonCount());
  await page.evaluate(instrument);
  const running = await phase(page, seconds * 1000, true);
  await page.keyboard.press(" ");
  await page.waitForFunction(() => window.__up.paused());
  await page.waitForTimeout(500);
  const paused = await phase(page, Math.min(5, seconds) * 1000, true);
  const result = {
    balloons: count,
    room_m: [side, side],
    viewport,
    chromium: browser.version(),
    renderer: "SwiftShader (CPU)",
    load_to_first_frames_s: Math.round(loadSeconds * 10) / 10,
    running,
    paused_drawing_only: { frame_ms: paused.frame_ms, fps: paused.fps, render_call_ms: paused.render_call_ms, input_delay_ms: paused.input_delay_ms, input_to_frame_ms: paused.input_to_frame_ms },
    page_errors: errors,
  };
  console.log(JSON.stringify(result));
} finally {
  await browser.close();
  await server.close();
}
