// The physics worker: owns the engine, steps it at a fixed timestep and sends
// poses to the main thread in ping-pong buffers. The main thread never waits
// for physics: with thousands of balloons a step may take longer than a frame,
// and the page still draws and answers input. In time-lapse (a rate above 1)
// each tick asks the engine to advance rate × the tick's time within a budget
// of steps (timeLapse.ts); every simulated second to minute it looks at where
// the balloons float and sends that for the plot.

import { Engine, glueUrl, type GlueModule } from "./engine";
import { DEFAULT_POOL, keepThreadsAwake, moduleUrl, startEngine, type PoolSettings, type StartedEngine } from "./threadPool";
import { RIBBON_POINT_STRIDE, checkLayout, frameFloats, frameViews } from "./frameLayout";
import type { FromWorker, ToWorker, WorldInfo } from "./protocol";
import { TimeLapse, censusInterval } from "./timeLapse";
import { ForceProbe, checkForceLayout } from "./forcesFrame";
import { measureSteps } from "./stepMeter";
import { AirSampler } from "./airSampler";
import { checkAirLayout } from "./airLayout";

/** Most steps taken in one tick; beyond that the simulation runs slow rather than spiral. */
const MAX_STEPS_PER_TICK = 4;
/** How often stats go to the HUD, ms. */
const STATS_INTERVAL_MS = 250;
/** Most contacts sent per frame to the debug view (8 floats each: 1 MiB). */
const MAX_DRAWN_CONTACTS = 32_768;
/** Restarts after a trap before the worker gives up. */
const MAX_RESTARTS = 3;

const scope = self as unknown as DedicatedWorkerGlobalScope;

const now = () => performance.timeOrigin + performance.now();

/** Everything the worker changes as it runs, in one place. */
class WorkerState {
  engine: Engine | null = null;
  /** The module's bytes and its glue's URL, to instantiate it afresh if it ever traps. */
  wasmBytes: ArrayBuffer | null = null;
  glueHref = "";
  /** Threads that step the engine, and whether the page may share memory with workers (else one thread). */
  threads = 1;
  isolated = false;
  /** How the pool runs beside the page's threads (threadPool.ts), its spinning switch, and whether the page draws. */
  pool: PoolSettings = DEFAULT_POOL;
  setKeepAwake: StartedEngine["setKeepAwake"] = null;
  drawing = true;
  /** The engine once the module is instantiated (validation requests wait for it). */
  started: Promise<Engine> | null = null;
  /** The scene of the current world, to rebuild it after a trap. */
  currentSceneJson: string | null = null;
  restarts = 0;
  /** Whether frames carry the step's contacts (the debug view is on). */
  sendContacts = false;
  dtMs = 1000 / 60;
  paletteSize = 1;
  paused = false;
  pendingSingleSteps = 0;
  accumulator = 0;
  lastTick = 0;
  steps = 0;
  /** The time-lapse rate and what it achieves. */
  readonly lapse = new TimeLapse();
  /** Simulated time of the next look at where the balloons float, s. */
  nextCensus = 0;
  /** Whether the last time-lapse tick ran out of steps before its span: the next one starts at once. */
  lapseBehind = false;
  /** Bumped whenever bodies are added or removed or the world is rebuilt: picks name the version they were made in. */
  version = 0;
  versionSent = -1;
  /** Whether the page lacks a frame of the current state. */
  dirty = true;
  lastStats = 0;
  stepsSinceStats = 0;
  tickTimer: ReturnType<typeof setTimeout> | null = null;
  /** Buffers the worker may fill; the main thread returns them after use. */
  freeBuffers: ArrayBuffer[] = [];
  lastStepTime = now();
  /** Poses before the last step of a tick, for interpolation; reused, grown only with the world. */
  previousPoses = new Float32Array(0);
  /** Ribbon points before the last step of a tick, likewise. */
  previousRibbons = new Float32Array(0);
}

const state = new WorkerState();
/** Whose forces the engine records, and the selected body. */
const probe = new ForceProbe();
/** The air's sources in the frames, and its field while shown. */
const air = new AirSampler();

/** The pool's threads spin through a step or sleep between its passes, as the settings and the page's drawing say. */
function applyKeepAwake(): void {
  state.setKeepAwake?.(keepThreadsAwake(state.pool, state.threads, navigator.hardwareConcurrency, state.drawing));
}

function post(message: FromWorker, transfer: Transferable[] = []): void {
  scope.postMessage(message, transfer);
}

function fail(error: unknown, fatal: boolean): void {
  post({ type: "error", message: error instanceof Error ? error.message : String(error), fatal });
}

function worldInfo(e: Engine): WorldInfo {
  const info = e.worldInfo();
  const trees = [];
  for (let m = 0; m < e.modelCount(); m++) trees.push(e.modelTree(m));
  // Latex balloons are drawn with the page's OBJ; foil ones need the engine's pillow.
  const foilMeshes = info.foil.map((foil, m) => (foil ? e.modelMesh(m) : null));
  return {
    sceneJson: e.sceneJson(),
    defaultSceneJson: e.defaultSceneJson(),
    room: e.room(),
    furniture: e.furniture(),
    trees,
    palette: info.colors,
    colorNames: info.color_names,
    diameters: info.diameters,
    foilMeshes,
    finishes: info.finishes,
    dt: info.dt,
    capacity: e.capacity(),
    constants: e.constants,
    threads: state.threads,
    isolated: state.isolated,
  };
}

/**
 * Builds the world from `sceneJson` (default scene when null) and announces
 * it, unless `announce` is false (the caller then does, with the info returned).
 */
function load(sceneJson: string | null, sceneToml?: string, announce = true): WorldInfo | null {
  if (!state.engine) return null;
  if (sceneToml !== undefined) state.engine.loadSceneToml(sceneToml);
  else if (sceneJson === null) state.engine.loadDefaultScene();
  else state.engine.loadSceneJson(sceneJson);
  probe.worldRebuilt();
  const info = worldInfo(state.engine);
  air.worldRebuilt(info.room.vertices);
  state.currentSceneJson = info.sceneJson;
  state.dtMs = info.dt * 1000;
  state.paletteSize = Math.max(1, info.palette.length);
  state.steps = 0;
  state.nextCensus = 0;
  state.accumulator = 0;
  state.version++;
  state.dirty = true;
  if (announce) post({ type: "ready", info });
  return info;
}

/** Takes a free buffer of at least `bytes`, or allocates one (only when the world grew). */
function takeBuffer(bytes: number): ArrayBuffer | null {
  const i = state.freeBuffers.findIndex((b) => b.byteLength >= bytes);
  if (i >= 0) return state.freeBuffers.splice(i, 1)[0];
  if (state.freeBuffers.length === 0) return null;
  // Only too-small buffers are free: replace one with a roomier one.
  state.freeBuffers.pop();
  return new ArrayBuffer(Math.ceil(bytes * 1.5));
}

interface Previous {
  poses: Float32Array;
  ribbons: Float32Array;
}

function sendFrame(previous: Previous | null): void {
  if (!state.engine) return;
  const count = state.engine.bodyCount();
  const ribbonFloats = state.engine.ribbonPointCount() * RIBBON_POINT_STRIDE;
  const contacts = state.sendContacts ? state.engine.contacts(MAX_DRAWN_CONTACTS) : null;
  const contactCount = contacts?.count ?? 0;
  const buffer = takeBuffer(Math.max(4, frameFloats(count, contactCount, ribbonFloats) * 4));
  if (!buffer) return; // the main thread still holds every buffer: send on return
  const out = frameViews(buffer, count, contactCount, ribbonFloats);
  // Copy each view before the next call: writing poses or ribbon points may
  // grow wasm memory, which detaches the views taken before.
  if (contacts) out.contacts.set(contacts.view);
  const current = state.engine.poses();
  out.prev.set(previous && previous.poses.length === current.length ? previous.poses : current);
  out.curr.set(current);
  const ribbons = state.engine.ribbonPoints();
  out.ribbonsPrev.set(previous && previous.ribbons.length === ribbons.length ? previous.ribbons : ribbons);
  out.ribbonsCurr.set(ribbons);
  out.scales.set(state.engine.bodyScales());
  out.squash.set(state.engine.bodySquash());
  const frame: FromWorker = {
    type: "frame",
    buffer,
    count,
    ribbonFloats,
    contactCount,
    contactTotal: contacts?.total ?? 0,
    version: state.version,
    stepTime: state.lastStepTime,
    simTime: state.engine.simTime(),
    steps: state.steps,
    paused: state.paused,
    airTemperatureC: state.engine.airTemperatureC(),
    rate: state.lapse.rate,
    achievedRate: state.lapse.lapsing ? state.lapse.achieved : 1,
  };
  const forces = probe.collect(state.engine);
  if (forces) frame.forces = forces;
  const airSources = air.sources(state.engine);
  if (airSources) frame.airSources = airSources;
  if (state.versionSent !== state.version) {
    frame.colors = state.engine.colors().slice();
    frame.models = state.engine.models().slice();
    frame.ribbons = state.engine.ribbons();
    state.versionSent = state.version;
  }
  state.dirty = false;
  // What the page was sent is what "Export last 10 s" writes.
  state.engine.recordExportFrame();
  const transfer: Transferable[] = forces ? [buffer, forces.rows.buffer] : [buffer];
  if (airSources) transfer.push(airSources.buffer);
  post(frame, transfer);
}

/**
 * A trap (a panic inside the module) leaves it unusable: instantiate it
 * afresh and rebuild the scene, saying so. Returns whether `error` was one.
 */
function restartAfterTrap(error: unknown): boolean {
  if (!(error instanceof WebAssembly.RuntimeError) || !state.wasmBytes) return false;
  state.engine = null;
  state.restarts++;
  if (state.restarts > MAX_RESTARTS) {
    fail(new Error(`the physics engine stopped ${state.restarts} times (last: ${error.message}); reload the page`), true);
    return true;
  }
  fail(new Error(`the physics engine stopped (${error.message}) and was restarted: the scene starts again`), false);
  const scene = state.currentSceneJson;
  const bytes = state.wasmBytes;
  // A glue module holds one instance: a fresh import gives a fresh one (and a
  // threaded one a fresh pool, whose start lets the old pool's workers go).
  state.started = Engine.importGlue(state.glueHref, state.restarts)
    .then((glue) => startEngine(glue, bytes, state.threads, state.isolated, state.pool))
    .then((started) => {
      state.setKeepAwake = started.setKeepAwake;
      applyKeepAwake();
      return started.engine;
    });
  state.started
    .then((e) => {
      state.engine = e;
      try {
        load(scene);
      } catch (err) {
        fail(err, false);
        load(null);
      }
      schedule();
    })
    .catch((err) => fail(err, true));
  return true;
}

/** A reused array of at least `length` floats (grown only with the world). */
function grown(array: Float32Array<ArrayBuffer>, length: number): Float32Array<ArrayBuffer> {
  return array.length < length ? new Float32Array(Math.ceil(length * 1.5)) : array;
}

/** Keeps the poses and ribbon points now, for interpolation toward the next ones. */
function capturePrevious(engine: Engine): Previous {
  const poses = engine.poses();
  state.previousPoses = grown(state.previousPoses, poses.length);
  const previousPoses = state.previousPoses.subarray(0, poses.length);
  previousPoses.set(poses);
  const ribbons = engine.ribbonPoints();
  state.previousRibbons = grown(state.previousRibbons, ribbons.length);
  const previousRibbons = state.previousRibbons.subarray(0, ribbons.length);
  previousRibbons.set(ribbons);
  return { poses: previousPoses, ribbons: previousRibbons };
}

function stepN(n: number): Previous | null {
  if (!state.engine || n <= 0) return null;
  if (n > 1) state.engine.step(n - 1);
  const previous = capturePrevious(state.engine);
  state.engine.step(1);
  state.steps += n;
  state.stepsSinceStats += n;
  state.lastStepTime = now();
  return previous;
}

/** One time-lapse tick of `realSeconds`: advances rate × that, within the step budget; null when nothing moved on. */
function lapseTick(realSeconds: number): Previous | null {
  const engine = state.engine;
  if (!engine) return null;
  const plan = state.lapse.plan(realSeconds);
  const seconds = Math.min(plan.seconds, engine.constants.max_advance_s);
  if (seconds <= 0) return null;
  const previous = capturePrevious(engine);
  const start = performance.now();
  const done = engine.advance(seconds, Math.min(plan.maxSteps, engine.constants.max_steps_per_call));
  state.lapse.record(done, performance.now() - start, realSeconds);
  // Half a step short is done (the engine's clock sums f32 steps).
  state.lapseBehind = done.seconds < seconds - state.dtMs / 2000;
  state.steps += done.steps;
  state.stepsSinceStats += done.steps;
  state.lastStepTime = now();
  return previous;
}

/** Looks at where the balloons float once the clock has passed the next look's time, and sends it. */
function census(): void {
  const engine = state.engine;
  if (!engine || engine.simTime() < state.nextCensus) return;
  const c = engine.floatCounts();
  const total = Math.max(1, c.ceiling + c.hovering + c.floor);
  post({
    type: "census",
    sample: { t: c.time_s, ceiling: c.ceiling / total, hovering: c.hovering / total, floor: c.floor / total, meanLiftFraction: c.mean_lift_fraction },
  });
  state.nextCensus = c.time_s + censusInterval(state.lapse.rate);
}

function tick(): void {
  state.tickTimer = null;
  const t = now();
  let due = 0;
  const lapsing = !!state.engine && !state.paused && state.lapse.lapsing;
  if (lapsing) {
    state.accumulator = 0;
  } else if (state.engine && !state.paused) {
    state.accumulator += t - state.lastTick;
    due = Math.floor(state.accumulator / state.dtMs);
    if (due > MAX_STEPS_PER_TICK) {
      due = MAX_STEPS_PER_TICK;
      state.accumulator = 0; // fall behind gracefully: slow motion, not a spiral
    } else {
      state.accumulator -= due * state.dtMs;
    }
  } else {
    state.accumulator = 0;
  }
  if (state.engine && state.paused && state.pendingSingleSteps > 0) {
    due = state.pendingSingleSteps;
    state.pendingSingleSteps = 0;
  }
  const realSeconds = (t - state.lastTick) / 1000;
  state.lastTick = t;
  try {
    if (state.engine) probe.apply(state.engine);
    const previous = lapsing ? lapseTick(realSeconds) : stepN(due);
    if (previous) probe.stepped();
    census();
    if (previous || state.dirty) sendFrame(previous);
    const field = state.engine ? air.sample(state.engine, t) : null;
    if (field) post({ type: "airField", field }, [field.cells.buffer]);
    if (state.engine && t - state.lastStats > STATS_INTERVAL_MS) {
      const seconds = (t - state.lastStats) / 1000;
      post({ type: "stats", stats: state.engine.stats(), stepsPerSecond: state.lastStats > 0 ? state.stepsSinceStats / seconds : 0 });
      state.lastStats = t;
      state.stepsSinceStats = 0;
    }
  } catch (e) {
    if (restartAfterTrap(e)) return;
    fail(e, false);
    state.paused = true;
  }
  schedule();
}

function schedule(): void {
  if (state.tickTimer !== null) return;
  // A time-lapse that fell behind steps on at once: the worker's thread is its
  // own, and each tick still ends within its budget to send a frame and read messages.
  const behind = !state.paused && state.lapse.lapsing && state.lapseBehind;
  const wait = state.paused ? 50 : behind ? 0 : Math.max(0, state.dtMs - state.accumulator - (now() - state.lastTick));
  state.tickTimer = setTimeout(tick, wait);
}

function handle(msg: ToWorker): void {
  switch (msg.type) {
    case "init": {
      // Threads need memory shared between workers, which only an isolated page has.
      const isolated = self.crossOriginIsolated === true;
      const wasmUrl = moduleUrl(msg.wasmUrl, msg.threads, isolated);
      state.glueHref = glueUrl(wasmUrl);
      state.started = Promise.all([Engine.fetchBytes(wasmUrl), Engine.importGlue(state.glueHref)]).then(async ([bytes, glue]: [ArrayBuffer, GlueModule]) => {
        state.wasmBytes = bytes;
        state.pool = msg.pool;
        const started = await startEngine(glue, bytes, msg.threads, isolated, msg.pool);
        state.threads = started.threads;
        state.isolated = started.isolated;
        state.setKeepAwake = started.setKeepAwake;
        applyKeepAwake();
        checkLayout(started.engine.constants);
        checkForceLayout(started.engine.constants);
        checkAirLayout(started.engine.constants);
        return started.engine;
      });
      state.started
        .then((e) => {
          state.engine = e;
          for (let i = 0; i < 3; i++) state.freeBuffers.push(new ArrayBuffer(4096));
          try {
            load(msg.sceneJson);
          } catch (err) {
            // The scene was refused: say why, then fall back to the default scene.
            fail(err, false);
            load(null);
          }
          state.lastTick = now();
          schedule();
        })
        .catch((err) => fail(err, true));
      return;
    }
    case "validate": {
      // The engine is the page's only scene validator; asked before it has started, the answer waits.
      const { id, sceneJson } = msg;
      const answer = (error: string | null) => post({ type: "validated", id, error });
      if (!state.started) answer("the physics engine has not been started");
      else state.started.then((e) => answer(e.validateScene(sceneJson))).catch((err) => answer(err instanceof Error ? err.message : String(err)));
      return;
    }
    case "hash": {
      const e = state.engine;
      if (e) post({ type: "hash", id: msg.id, hash: BigInt.asUintN(64, e.stateHash()).toString(16).padStart(16, "0"), steps: state.steps });
      return;
    }
    case "exportGltf": {
      const e = state.engine;
      try {
        if (!e) throw new Error("the physics engine has not been started");
        const bytes = e.exportGltf();
        const glb = bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength) as ArrayBuffer;
        post({ type: "gltf", id: msg.id, glb, error: null }, [glb]);
      } catch (err) {
        post({ type: "gltf", id: msg.id, glb: null, error: err instanceof Error ? err.message : String(err) });
      }
      return;
    }
    case "debug":
      state.sendContacts = msg.on;
      state.dirty = true;
      return;
    case "drawing":
      state.drawing = msg.on;
      applyKeepAwake();
      return;
    case "showAir":
      air.setShow(msg.on);
      return;
    case "return":
      state.freeBuffers.push(msg.buffer);
      if (state.dirty) sendFrame(null);
      return;
    default:
      break;
  }
  if (!state.engine) return;
  try {
    switch (msg.type) {
      case "load":
        try {
          load(msg.sceneJson);
        } catch (err) {
          fail(err, false);
        }
        break;
      case "loadToml":
        try {
          load(null, msg.sceneToml);
        } catch (err) {
          fail(err, false);
        }
        break;
      case "select":
        if (msg.index < 0 || msg.version === state.version) probe.select(msg.index);
        probe.apply(state.engine);
        state.dirty = true;
        break;
      case "forcesOnAll":
        probe.setAll(msg.on);
        probe.apply(state.engine);
        state.dirty = true;
        break;
      case "pause":
        state.paused = msg.paused;
        state.dirty = true;
        state.lastTick = now();
        break;
      case "step":
        state.pendingSingleSteps++;
        break;
      case "rate":
        state.lapse.setRate(msg.rate);
        state.accumulator = 0;
        state.lastTick = now();
        // The plot's grain follows the rate: the next look comes at the new pace.
        state.nextCensus = Math.min(state.nextCensus, state.engine.simTime() + censusInterval(msg.rate));
        state.dirty = true;
        break;

      case "addOnFloor": {
        const color = state.engine.bodyCount() % state.paletteSize;
        state.engine.addBalloonOnFloor(msg.x, msg.z, color);
        state.version++;
        state.dirty = true;
        break;
      }
      case "pop":
        if (msg.version === state.version) {
          probe.removed(msg.index, state.engine.bodyCount());
          state.engine.remove(msg.index);
          state.version++;
          state.dirty = true;
        }
        break;
      case "grab":
        if (msg.version === state.version) state.engine.grab(msg.index, ...msg.point);
        break;
      case "grabRibbon":
        if (msg.version === state.version) state.engine.grabRibbon(msg.ribbon, msg.point, ...msg.target);
        break;
      case "live":
        state.engine.applyLive(msg.setting);
        // A setting may tie or untie ribbons: the page reads the tables afresh.
        state.version++;
        state.dirty = true;
        // The world's scene now: a restart after a trap rebuilds it with the setting.
        state.currentSceneJson = state.engine.sceneJson();
        post({ type: "scene", sceneJson: state.currentSceneJson });
        break;
      case "dragTo":
        state.engine.dragTo(...msg.point);
        break;
      case "air":
        state.engine.applyAir(msg.command);
        air.changed();
        state.dirty = true;
        // The scene holds the page's fans: a rebuilt world and the share link keep them.
        state.currentSceneJson = state.engine.sceneJson();
        post({ type: "scene", sceneJson: state.currentSceneJson });
        break;
      case "release":
        state.engine.release();
        break;
      case "measureSteps": {
        // The page rebuilds its world on "ready": told after the window, so that
        // the rebuild does not take cores from the steps being timed.
        const info = load(state.currentSceneJson, undefined, false);
        // Each thread's part of each stage, timed for this window only (two clock reads a task).
        state.engine.setThreadTiming(msg.threadTimes);
        let measured;
        try {
          measured = measureSteps(state.engine, msg.steps);
        } finally {
          state.engine.setThreadTiming(false);
        }
        post({ type: "stepsMeasured", ...measured });
        state.steps = msg.steps;
        if (info) post({ type: "ready", info });
        break;
      }
    }
  } catch (err) {
    if (restartAfterTrap(err)) return;
    fail(err, false);
  }
  if (state.tickTimer !== null && state.dirty) {
    clearTimeout(state.tickTimer);
    state.tickTimer = null;
  }
  schedule();
}

scope.onmessage = (e: MessageEvent<ToWorker>) => handle(e.data);
