// The physics worker: owns the engine, steps it at a fixed timestep and sends
// poses to the main thread in ping-pong buffers. The main thread never waits
// for physics: with thousands of balloons a step may take longer than a frame,
// and the page still draws and answers input.

import { Engine, glueUrl, type GlueModule } from "./engine";
import { checkLayout, frameFloats, frameViews } from "./frameLayout";
import type { FromWorker, ToWorker, WorldInfo } from "./protocol";

/** Most steps taken in one tick; beyond that the simulation runs slow rather than spiral. */
const MAX_STEPS_PER_TICK = 4;
/** How often stats go to the HUD, ms. */
const STATS_INTERVAL_MS = 250;
/** Most contacts sent per frame to the debug view (8 floats each: 1 MiB). */
const MAX_DRAWN_CONTACTS = 32_768;
/** Restarts after a trap before the worker gives up. */
const MAX_RESTARTS = 3;

const scope = self as unknown as DedicatedWorkerGlobalScope;

let engine: Engine | null = null;
/** The module's bytes and its glue's URL, to instantiate it afresh if it ever traps. */
let wasmBytes: ArrayBuffer | null = null;
let glueHref = "";
/** The engine once the module is instantiated (validation requests wait for it). */
let started: Promise<Engine> | null = null;
/** The scene of the current world, to rebuild it after a trap. */
let currentSceneJson: string | null = null;
let restarts = 0;
/** Whether frames carry the step's contacts (the debug view is on). */
let sendContacts = false;
let dtMs = 1000 / 60;
let paletteSize = 1;
let paused = false;
let pendingSingleSteps = 0;
let accumulator = 0;
let lastTick = 0;
let simTime = 0;
let steps = 0;
let version = 0;
let versionSent = -1;
let dirty = true;
let lastStats = 0;
let stepsSinceStats = 0;
let tickTimer: ReturnType<typeof setTimeout> | null = null;
/** Buffers the worker may fill; the main thread returns them after use. */
const freeBuffers: ArrayBuffer[] = [];

const now = () => performance.timeOrigin + performance.now();

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
  return {
    sceneJson: e.sceneJson(),
    defaultSceneJson: e.defaultSceneJson(),
    room: e.room(),
    trees,
    palette: info.colors,
    colorNames: info.color_names,
    diameters: info.diameters,
    dt: info.dt,
    capacity: e.capacity(),
    constants: e.constants,
  };
}

/** Builds the world from `sceneJson` (default scene when null) and announces it. */
function load(sceneJson: string | null): void {
  if (!engine) return;
  if (sceneJson === null) engine.loadDefaultScene();
  else engine.loadSceneJson(sceneJson);
  const info = worldInfo(engine);
  currentSceneJson = info.sceneJson;
  dtMs = info.dt * 1000;
  paletteSize = Math.max(1, info.palette.length);
  simTime = 0;
  steps = 0;
  accumulator = 0;
  version++;
  dirty = true;
  post({ type: "ready", info });
}

/** Takes a free buffer of at least `bytes`, or allocates one (only when the world grew). */
function takeBuffer(bytes: number): ArrayBuffer | null {
  const i = freeBuffers.findIndex((b) => b.byteLength >= bytes);
  if (i >= 0) return freeBuffers.splice(i, 1)[0];
  if (freeBuffers.length === 0) return null;
  // Only too-small buffers are free: replace one with a roomier one.
  freeBuffers.pop();
  return new ArrayBuffer(Math.ceil(bytes * 1.5));
}

function sendFrame(previous: Float32Array | null): void {
  if (!engine) return;
  const count = engine.bodyCount();
  const contacts = sendContacts ? engine.contacts(MAX_DRAWN_CONTACTS) : null;
  const contactCount = contacts?.count ?? 0;
  const buffer = takeBuffer(Math.max(4, frameFloats(count, contactCount) * 4));
  if (!buffer) return; // the main thread still holds every buffer: send on return
  const out = frameViews(buffer, count, contactCount);
  // Copy the contacts before asking for poses: writing poses may grow wasm memory,
  // which detaches the contacts view.
  if (contacts) out.contacts.set(contacts.view);
  const current = engine.poses();
  out.prev.set(previous && previous.length === current.length ? previous : current);
  out.curr.set(current);
  const frame: FromWorker = {
    type: "frame",
    buffer,
    count,
    contactCount,
    contactTotal: contacts?.total ?? 0,
    version,
    stepTime: lastStepTime,
    simTime,
    steps,
    paused,
  };
  if (versionSent !== version) {
    frame.colors = engine.colors().slice();
    frame.models = engine.models().slice();
    versionSent = version;
  }
  dirty = false;
  post(frame, [buffer]);
}

/**
 * A trap (a panic inside the module) leaves it unusable: instantiate it
 * afresh and rebuild the scene, saying so. Returns whether `error` was one.
 */
function restartAfterTrap(error: unknown): boolean {
  if (!(error instanceof WebAssembly.RuntimeError) || !wasmBytes) return false;
  engine = null;
  restarts++;
  if (restarts > MAX_RESTARTS) {
    fail(new Error(`the physics engine stopped ${restarts} times (last: ${error.message}); reload the page`), true);
    return true;
  }
  fail(new Error(`the physics engine stopped (${error.message}) and was restarted: the scene starts again`), false);
  const scene = currentSceneJson;
  const bytes = wasmBytes;
  // A glue module holds one instance: a fresh import gives a fresh one.
  started = Engine.importGlue(glueHref, restarts).then((glue) => Engine.load(glue, bytes));
  started
    .then((e) => {
      engine = e;
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

let lastStepTime = now();
/** Poses before the last step of a tick, for interpolation; reused, grown only with the world. */
let previousPoses = new Float32Array(0);

function stepN(n: number): Float32Array | null {
  if (!engine || n <= 0) return null;
  if (n > 1) engine.step(n - 1);
  const poses = engine.poses();
  if (previousPoses.length < poses.length) previousPoses = new Float32Array(Math.ceil(poses.length * 1.5));
  const previous = previousPoses.subarray(0, poses.length);
  previous.set(poses);
  engine.step(1);
  steps += n;
  stepsSinceStats += n;
  simTime += (n * dtMs) / 1000;
  lastStepTime = now();
  return previous;
}

function tick(): void {
  tickTimer = null;
  const t = now();
  let due = 0;
  if (engine && !paused) {
    accumulator += t - lastTick;
    due = Math.floor(accumulator / dtMs);
    if (due > MAX_STEPS_PER_TICK) {
      due = MAX_STEPS_PER_TICK;
      accumulator = 0; // fall behind gracefully: slow motion, not a spiral
    } else {
      accumulator -= due * dtMs;
    }
  } else {
    accumulator = 0;
  }
  if (engine && paused && pendingSingleSteps > 0) {
    due = pendingSingleSteps;
    pendingSingleSteps = 0;
  }
  lastTick = t;
  try {
    const previous = stepN(due);
    if (due > 0 || dirty) sendFrame(previous);
    if (engine && t - lastStats > STATS_INTERVAL_MS) {
      const seconds = (t - lastStats) / 1000;
      post({ type: "stats", stats: engine.stats(), stepsPerSecond: lastStats > 0 ? stepsSinceStats / seconds : 0 });
      lastStats = t;
      stepsSinceStats = 0;
    }
  } catch (e) {
    if (restartAfterTrap(e)) return;
    fail(e, false);
    paused = true;
  }
  schedule();
}

function schedule(): void {
  if (tickTimer !== null) return;
  const wait = paused ? 50 : Math.max(0, dtMs - accumulator - (now() - lastTick));
  tickTimer = setTimeout(tick, wait);
}

function handle(msg: ToWorker): void {
  switch (msg.type) {
    case "init":
      glueHref = glueUrl(msg.wasmUrl);
      started = Promise.all([Engine.fetchBytes(msg.wasmUrl), Engine.importGlue(glueHref)]).then(([bytes, glue]: [ArrayBuffer, GlueModule]) => {
        wasmBytes = bytes;
        const e = Engine.load(glue, bytes);
        checkLayout(e.constants);
        return e;
      });
      started
        .then((e) => {
          engine = e;
          for (let i = 0; i < 3; i++) freeBuffers.push(new ArrayBuffer(4096));
          try {
            load(msg.sceneJson);
          } catch (err) {
            // The scene was refused: say why, then fall back to the default scene.
            fail(err, false);
            load(null);
          }
          lastTick = now();
          schedule();
        })
        .catch((err) => fail(err, true));
      return;
    case "validate": {
      // The engine is the page's only scene validator; asked before it has started, the answer waits.
      const { id, sceneJson } = msg;
      const answer = (error: string | null) => post({ type: "validated", id, error });
      if (!started) answer("the physics engine has not been started");
      else started.then((e) => answer(e.validateScene(sceneJson))).catch((err) => answer(err instanceof Error ? err.message : String(err)));
      return;
    }
    case "debug":
      sendContacts = msg.on;
      dirty = true;
      return;
    case "return":
      freeBuffers.push(msg.buffer);
      if (dirty) sendFrame(null);
      return;
    default:
      break;
  }
  if (!engine) return;
  try {
    switch (msg.type) {
      case "load":
        try {
          load(msg.sceneJson);
        } catch (err) {
          fail(err, false);
        }
        break;
      case "pause":
        paused = msg.paused;
        dirty = true;
        lastTick = now();
        break;
      case "step":
        pendingSingleSteps++;
        break;

      case "addOnFloor": {
        const color = engine.bodyCount() % paletteSize;
        engine.addBalloonOnFloor(msg.x, msg.z, color);
        version++;
        dirty = true;
        break;
      }
      case "pop":
        if (msg.version === version) {
          engine.remove(msg.index);
          version++;
          dirty = true;
        }
        break;
      case "grab":
        if (msg.version === version) engine.grab(msg.index, ...msg.point);
        break;
      case "dragTo":
        engine.dragTo(...msg.point);
        break;
      case "release":
        engine.release();
        break;
    }
  } catch (err) {
    if (restartAfterTrap(err)) return;
    fail(err, false);
  }
  if (tickTimer !== null && dirty) {
    clearTimeout(tickTimer);
    tickTimer = null;
  }
  schedule();
}

scope.onmessage = (e: MessageEvent<ToWorker>) => handle(e.data);
