// Main-thread side of the physics worker: sends commands, keeps the newest
// frame of poses, hands the previous buffer back (ping-pong), and tells how
// far between the two steps of a frame the display is (interpolation).

import type { AirCommand, EngineStats, LiveSetting, RibbonTables } from "./engine";
import type { AirField } from "./airLayout";
import type { CensusSample, Frame, FromWorker, ToWorker, Vec3Tuple, WorldInfo } from "./protocol";
import { frameViews } from "./frameLayout";
import type { ForcesPayload } from "./forcesFrame";
import { setEngineConstants } from "../scene/sceneSchema";
import type { StepsMeasured } from "./stepMeter";
import { DEFAULT_POOL, type PoolSettings } from "./threadPool";

const NO_AIR_SOURCES: Float32Array = new Float32Array(0);

export interface BridgeEvents {
  ready(info: WorldInfo): void;
  frame(frame: Frame): void;
  stats(stats: EngineStats, stepsPerSecond: number): void;
  /** A look at where the balloons float (for the plot). */
  census(sample: CensusSample): void;
  error(message: string, fatal: boolean): void;
  /** The engine's scene after a live setting, as JSON. */
  scene(sceneJson: string): void;
  /** The air sampled on a grid of the room (while "show air" is on). */
  airField?(field: AirField): void;
}

export class SimBridge {
  private worker: Worker;
  private wasmUrl = "";
  /** How the engine's pool runs (kept for `restart`). */
  private pool: PoolSettings = DEFAULT_POOL;
  private rate = 1;
  /** Whether the page draws its frames (kept for `restart`: a fresh worker assumes it does). */
  private drawing = true;
  /** What a restarted engine is given once it is ready (it drops commands before). */
  private restore: { paused: boolean; rate: number } | null = null;
  /** The newest frame, drawn every animation frame until the next one arrives. */
  current: Frame | null = null;
  prev = new Float32Array(0);
  curr = new Float32Array(0);
  /** The current step's contacts (empty unless the debug view is on). */
  contacts = new Float32Array(0);
  colors: Uint32Array = new Uint32Array(0);
  models: Uint32Array = new Uint32Array(0);
  /** Every ribbon's points before and after the frame's last step (`RIBBON_POINT_STRIDE` each). */
  ribbonsPrev = new Float32Array(0);
  ribbonsCurr = new Float32Array(0);
  /** Each body's size over its shape's in the current frame (its gas's). */
  scales = new Float32Array(0);
  /** Each body's deepest dent since the frame before (`SQUASH_STRIDE` each; zeros: none). */
  squash = new Float32Array(0);
  /** Each ribbon's first point, balloon and colour,. */
  ribbons: RibbonTables = { offsets: new Uint32Array(1), bodies: new Uint32Array(0), colors: new Uint32Array(0), weights: new Float32Array(0) };
  info: WorldInfo | null = null;
  /** The newest frame's forces and selected body's card (null while nothing is probed). */
  forces: ForcesPayload | null = null;
  paused = false;
  /** The newest frame's air sources (sim/airLayout.ts; empty: still air). */
  airSources: Float32Array = new Float32Array(0);
  /** Validation requests waiting for the worker's answer, by id. */
  private readonly validations = new Map<number, (error: string | null) => void>();
  private nextValidation = 1;
  /** Step measurements waiting for the worker's answer, in order. */
  private readonly measurements: ((r: StepsMeasured) => void)[] = [];
  /** State hash requests waiting for the worker's answer, by id. */
  private readonly hashes = new Map<number, (answer: { hash: string; steps: number }) => void>();
  /** glTF exports waiting for the worker's answer, by id. */
  private readonly exports = new Map<number, (answer: { glb: ArrayBuffer | null; error: string | null }) => void>();

  constructor(private readonly events: BridgeEvents) {
    this.worker = this.startWorker();
  }

  private startWorker(): Worker {
    const worker = new Worker(new URL("./worker.ts", import.meta.url), { type: "module" });
    worker.onmessage = (e: MessageEvent<FromWorker>) => this.receive(e.data);
    worker.onerror = (e) => this.events.error(`the physics worker failed: ${e.message || "unknown error"}`, true);
    return worker;
  }

  private send(msg: ToWorker, transfer: Transferable[] = []): void {
    this.worker.postMessage(msg, transfer);
  }

  private receive(msg: FromWorker): void {
    switch (msg.type) {
      case "ready":
        setEngineConstants(msg.info.constants, msg.info.defaultSceneJson);
        this.info = msg.info;
        if (this.restore) {
          if (this.restore.paused) this.setPaused(true);
          if (this.restore.rate !== 1) this.setRate(this.restore.rate);
          this.restore = null;
        }
        this.events.ready(msg.info);
        break;
      case "frame": {
        const old = this.current;
        this.current = msg;
        const views = frameViews(msg.buffer, msg.count, msg.contactCount, msg.ribbonFloats);
        this.prev = views.prev;
        this.curr = views.curr;
        this.contacts = views.contacts;
        this.ribbonsPrev = views.ribbonsPrev;
        this.ribbonsCurr = views.ribbonsCurr;
        this.scales = views.scales;
        this.squash = views.squash;
        if (msg.colors) this.colors = msg.colors;
        if (msg.models) this.models = msg.models;
        if (msg.ribbons) this.ribbons = msg.ribbons;
        this.paused = msg.paused;
        this.forces = msg.forces ?? null;
        this.airSources = msg.airSources ?? NO_AIR_SOURCES;
        this.events.frame(msg);
        // The previous frame's buffer goes back to the worker for refilling.
        if (old) this.send({ type: "return", buffer: old.buffer }, [old.buffer]);
        break;
      }
      case "stats":
        this.events.stats(msg.stats, msg.stepsPerSecond);
        break;
      case "census":
        this.events.census(msg.sample);
        break;
      case "error":
        this.events.error(msg.message, msg.fatal);
        break;
      case "scene":
        this.events.scene(msg.sceneJson);
        break;
      case "validated":
        this.validations.get(msg.id)?.(msg.error);
        this.validations.delete(msg.id);
        break;
      case "stepsMeasured":
        this.measurements.shift()?.(msg);
        break;
      case "hash":
        this.hashes.get(msg.id)?.(msg);
        this.hashes.delete(msg.id);
        break;
      case "gltf":
        this.exports.get(msg.id)?.(msg);
        this.exports.delete(msg.id);
        break;
      case "airField":
        this.events.airField?.(msg.field);
        break;
    }
  }

  /** Display position between the frame's two steps, 0–1. */
  alpha(nowAbs: number): number {
    const f = this.current;
    if (!f || f.paused || !this.info) return 1;
    return Math.min(1, Math.max(0, (nowAbs - f.stepTime) / (this.info.dt * 1000)));
  }

  /** Starts the engine of module `wasmUrl` (the single-threaded one) on `threads` threads, its pool run as `pool` says, with `sceneJson` (null: the default scene). */
  init(wasmUrl: string, sceneJson: string | null, threads: number, pool: PoolSettings = DEFAULT_POOL): void {
    this.wasmUrl = wasmUrl;
    this.pool = pool;
    this.send({ type: "init", wasmUrl, sceneJson, threads, pool });
  }

  /**
   * A fresh worker and engine on `threads` threads, with `sceneJson` from its
   * start (rayon's pool has its size for the life of the module), paused and
   * at the time-lapse rate as before. Requests still waiting are answered as refused.
   */
  restart(sceneJson: string | null, threads: number): void {
    this.worker.terminate();
    for (const answer of this.validations.values()) answer("the physics engine was restarted");
    this.validations.clear();
    this.hashes.clear();
    for (const answer of this.exports.values()) answer({ glb: null, error: "the physics engine was restarted" });
    this.exports.clear();
    this.current = null;
    this.worker = this.startWorker();
    this.restore = { paused: this.paused, rate: this.rate };
    this.init(this.wasmUrl, sceneJson, threads, this.pool);
    if (!this.drawing) this.setDrawing(false);
  }

  /** The world's state hash (16 hex digits) and the steps taken since it was built. */
  stateHash(): Promise<{ hash: string; steps: number }> {
    const id = this.nextValidation++;
    return new Promise((resolve) => {
      this.hashes.set(id, resolve);
      this.send({ type: "hash", id });
    });
  }

  /** The last 10 s of frames the page was sent, as an animated glTF binary (.glb); rejects with the engine's reason. */
  exportGltf(): Promise<ArrayBuffer> {
    const id = this.nextValidation++;
    return new Promise((resolve, reject) => {
      this.exports.set(id, ({ glb, error }) => (glb ? resolve(glb) : reject(new Error(error ?? "no glTF"))));
      this.send({ type: "exportGltf", id });
    });
  }

  /**
   * Asks the engine whether it would load `sceneJson` (the page keeps no
   * scene schema of its own): resolves to the engine's message when it
   * refuses the scene, or null when it accepts it.
   */
  validate(sceneJson: string): Promise<string | null> {
    const id = this.nextValidation++;
    return new Promise((resolve) => {
      this.validations.set(id, resolve);
      this.send({ type: "validate", id, sceneJson });
    });
  }

  /**
   * Measurements: restarts the scene and times `steps` steps in the worker
   * (sim/stepMeter.ts), with each thread's part of each stage when
   * `threadTimes`; the page draws on meanwhile.
   */
  measureSteps(steps: number, threadTimes = false): Promise<StepsMeasured> {
    return new Promise((resolve) => {
      this.measurements.push(resolve);
      this.send({ type: "measureSteps", steps, threadTimes });
    });
  }

  /** Tells the worker whether the page draws its frames (the pool's spinning depends on it). */
  setDrawing(on: boolean): void {
    this.drawing = on;
    this.send({ type: "drawing", on });
  }

  load(sceneJson: string | null): void {
    this.send({ type: "load", sceneJson });
  }

  /** Builds the world from a scene file in TOML. */
  loadToml(sceneToml: string): void {
    this.send({ type: "loadToml", sceneToml });
  }

  /** Selects body `index` of the current frame (-1: none); the worker keeps following it. */
  select(index: number): void {
    this.send({ type: "select", index, version: this.current?.version ?? -1 });
  }

  /** Every balloon's forces in the frames, or only the selected one's. */
  setForcesOnAll(on: boolean): void {
    this.send({ type: "forcesOnAll", on });
  }

  setPaused(paused: boolean): void {
    this.paused = paused;
    this.send({ type: "pause", paused });
  }

  /** Asks for contacts in every frame (debug view on), or for none. */
  setDebug(on: boolean): void {
    this.send({ type: "debug", on });
  }

  /** Time-lapse: simulated seconds per real second (1: real time). */
  setRate(rate: number): void {
    this.rate = rate;
    this.send({ type: "rate", rate });
  }

  singleStep(): void {
    this.send({ type: "step" });
  }

  addOnFloor(x: number, z: number): void {
    this.send({ type: "addOnFloor", x, z });
  }

  pop(index: number): void {
    if (this.current) this.send({ type: "pop", index, version: this.current.version });
  }

  grab(index: number, point: Vec3Tuple): void {
    if (this.current) this.send({ type: "grab", index, version: this.current.version, point });
  }

  /** Holds point `point` of ribbon `ribbon` (the current frame's ribbon order) and pulls it toward `target`. */
  grabRibbon(ribbon: number, point: number, target: Vec3Tuple): void {
    if (this.current) this.send({ type: "grabRibbon", ribbon, point, version: this.current.version, target });
  }

  /** A live setting for the running world, forwarded as it is (`Engine.applyLive`). */
  live(setting: LiveSetting): void {
    this.send({ type: "live", setting });
  }

  /** A command of the air tools for the running world, forwarded as it is (`Engine.applyAir`). */
  air(command: AirCommand): void {
    this.send({ type: "air", command });
  }

  /** Asks for the air's field every quarter second or so ("show air" on), or for none. */
  setShowAir(on: boolean): void {
    this.send({ type: "showAir", on });
  }

  dragTo(point: Vec3Tuple): void {
    this.send({ type: "dragTo", point });
  }

  release(): void {
    this.send({ type: "release" });
  }
}
