// Typed wrapper over up-wasm's wasm-bindgen exports (crates/up-wasm/src/lib.rs).
// The glue (public/wasm/up_wasm.js) and its types (up_wasm.d.ts) are written
// by wasm-bindgen from the Rust crate, so the method signatures, the scene's
// types and the contract's constants all come from Rust; this wrapper adds
// camelCase names, views of wasm memory for the bulk data (re-created after
// each call, since memory may grow), and an `EngineError` carrying the
// engine's own error kind and message.

import type * as Glue from "../../public/wasm/up_wasm";
import { SQUASH_STRIDE } from "./frameLayout";

export type { AirCommand, AirGrid, FanDef } from "../../public/wasm/up_wasm";
export type { AdvanceReport, BodyCard, Constants, EngineStats, StageThreadTimes, Finish, FloatCounts, LiveRange, LiveSetting, NamedColor, Scene, SceneLimits, WorldSummary } from "../../public/wasm/up_wasm";

/** The glue module as `import()` returns it. */
export type GlueModule = typeof Glue;

/** A call the engine refused: `kind` is one of `constants.error_kinds`. */
export class EngineError extends Error {
  constructor(
    readonly kind: string,
    message: string,
  ) {
    super(message);
    this.name = `EngineError(${kind})`;
  }
}

/** One node of a balloon model's sphere tree, body frame. */
export interface TreeNode {
  center: [number, number, number];
  /** m */
  radius: number;
  /** 0 for the root. */
  depth: number;
  leaf: boolean;
}

/** The static room, as triangles (normals point into the room). */
export interface RoomMesh {
  vertices: Float32Array;
  triangles: Uint32Array;
}

/** The furniture's pieces together, world frame (the triangles the engine collides with). */
export interface FurnitureMesh {
  /** x, y, z per vertex, m. */
  vertices: Float32Array;
  /** Three per triangle, counter-clockwise seen from outside; empty without furniture. */
  triangles: Uint32Array;
}

/** A balloon model's surface, body frame (the frame the poses place). */
export interface ModelMesh {
  /** x, y, z per vertex (`constants.mesh_vertex_stride`). */
  positions: Float32Array;
  /** Unit, x, y, z per vertex. */
  normals: Float32Array;
  /** Three per triangle, counter-clockwise seen from outside. */
  indices: Uint32Array;
}

/** The last step's contacts, as `write_contacts` wrote them. */
export interface Contacts {
  /** `constants.contact_stride` floats per contact: a view, valid until the next call. */
  view: Float32Array;
  /** Contacts in `view`. */
  count: number;
  /** Contacts the step had in all (more than `count` when capped). */
  total: number;
}

/** Each ribbon's place in the points, its balloon and its colour, in the order of the points. */
export interface RibbonTables {
  /** First point of each ribbon, then the total: ribbons + 1 entries. */
  offsets: Uint32Array;
  /** Dense index of the balloon each ribbon is tied to. */
  bodies: Uint32Array;
  /** Colour of each ribbon, 0xRRGGBB (sRGB). */
  colors: Uint32Array;
  /** The weight at each ribbon's free end, kg (0: none). */
  weights: Float32Array;
}

/** The URL of the glue next to the module `up_wasm.wasm` (`up_wasm.js`). */
export function glueUrl(wasmUrl: string): string {
  return wasmUrl.replace(/\.wasm(?=$|[?#])/, ".js");
}

/**
 * Rethrows an error of the glue as an `EngineError` when it is one of the
 * engine's (its `name` is an error kind); other errors (a trap) pass as they are.
 */
function engineError(e: unknown, kinds: ReadonlySet<string>): unknown {
  return e instanceof Error && kinds.has(e.name) ? new EngineError(e.name, e.message) : e;
}

export class Engine {
  /** Every number and name the engine and the page agree on, read from the module. */
  readonly constants: Glue.Constants;
  private readonly kinds: ReadonlySet<string>;
  private readonly e: Glue.Engine;

  private constructor(
    private readonly glue: GlueModule,
    private readonly memory: WebAssembly.Memory,
  ) {
    this.constants = glue.constants();
    this.kinds = new Set(this.constants.error_kinds);
    this.e = new glue.Engine();
  }

  /**
   * Instantiates the module's `bytes` with its glue. A glue module holds one
   * instance: after a trap, import the glue afresh (`importGlue` with a new
   * `instance`) and load again.
   */
  static load(glue: GlueModule, bytes: BufferSource): Engine {
    const exports = glue.initSync({ module: bytes });
    return new Engine(glue, exports.memory);
  }

  /** Imports the glue at `url`; a different `instance` gives a fresh copy of it (no shared state). */
  static async importGlue(url: string, instance = 0): Promise<GlueModule> {
    const href = instance === 0 ? url : `${url}${url.includes("?") ? "&" : "?"}instance=${instance}`;
    return (await import(/* @vite-ignore */ href)) as GlueModule;
  }

  /** Fetches the module's bytes at `url` (instantiate them with `load`, again after a trap). */
  static async fetchBytes(url: string): Promise<ArrayBuffer> {
    const response = await fetch(url);
    if (!response.ok) throw new Error(`cannot load the physics engine ${url}: HTTP ${response.status}`);
    return response.arrayBuffer();
  }

  private call<T>(f: () => T): T {
    try {
      return f();
    } catch (e) {
      throw engineError(e, this.kinds);
    }
  }

  /** Reads and checks a scene in JSON as loading it would; the engine's message when refused, else null. */
  validateScene(json: string): string | null {
    try {
      this.glue.validate_scene(json);
      return null;
    } catch (e) {
      const error = engineError(e, this.kinds);
      if (error instanceof EngineError) return error.message;
      throw error;
    }
  }

  /** Builds the world from a scene in JSON (the web app's own format). */
  loadSceneJson(json: string): void {
    this.call(() => this.e.load_scene_json(json));
  }

  /** Builds the world from a scene in TOML (the CLI's files). */
  loadSceneToml(toml: string): void {
    this.call(() => this.e.load_scene_toml(toml));
  }

  /** Builds the default scene: the original UP room. */
  loadDefaultScene(): void {
    this.call(() => this.e.load_default_scene());
  }

  /** The loaded scene, as JSON with every default written out. */
  sceneJson(): string {
    return this.call(() => this.e.scene_json());
  }

  /** The default scene as JSON. Needs no world. */
  defaultSceneJson(): string {
    return this.call(() => this.glue.default_scene_json());
  }

  step(n = 1): void {
    this.call(() => this.e.step(n));
  }

  /**
   * Advances `seconds` of simulated time, stepping while anything moves and
   * jumping the gas alone while everything sleeps, in at most `maxSteps`
   * steps: says how far it got (less than asked when the steps ran out).
   */
  advance(seconds: number, maxSteps: number): Glue.AdvanceReport {
    return this.call(() => this.e.advance(seconds, maxSteps));
  }

  /** Simulated seconds since the world was built. */
  simTime(): number {
    return this.e.sim_time();
  }

  /** The room's air temperature now, °C. */
  airTemperatureC(): number {
    return this.call(() => this.e.air_temperature_c());
  }

  /**
   * Every body's size over its shape's (1 without gas), dense order: one
   * view of wasm memory, valid until the next call into the engine.
   */
  bodyScales(): Float32Array {
    const n = this.call(() => this.e.write_body_scales());
    return new Float32Array(this.memory.buffer, this.e.body_scales_ptr(), n);
  }

  /** Each body's deepest dent since the last call (`SQUASH_STRIDE` floats each; drawing only), then forgotten. */
  bodySquash(): Float32Array {
    const n = this.call(() => this.e.write_body_squash());
    return new Float32Array(this.memory.buffer, this.e.body_squash_ptr(), n * SQUASH_STRIDE);
  }

  /** Where the balloons float now, in all and per group (a look the engine's census remembers). */
  floatCounts(): Glue.FloatCounts {
    return this.call(() => this.e.float_counts());
  }

  bodyCount(): number {
    return this.e.body_count();
  }

  /** Most bodies the world accepts. */
  capacity(): number {
    return this.constants.capacity;
  }

  /**
   * Poses of all bodies (`constants.pose_stride` floats each), dense order:
   * one view of wasm memory, valid until the next call into the engine.
   */
  poses(): Float32Array {
    const n = this.call(() => this.e.write_poses());
    return new Float32Array(this.memory.buffer, this.e.poses_ptr(), n);
  }

  /** Colour index of every body, dense order (a view, valid until the next call). */
  colors(): Uint32Array {
    const n = this.call(() => this.e.write_colors_and_models());
    return new Uint32Array(this.memory.buffer, this.e.colors_ptr(), n);
  }

  /** Balloon model index of every body, dense order (a view, valid until the next call). */
  models(): Uint32Array {
    const n = this.call(() => this.e.write_colors_and_models());
    return new Uint32Array(this.memory.buffer, this.e.models_ptr(), n);
  }

  addBalloon(x: number, y: number, z: number, color: number, model = 0): void {
    this.call(() => this.e.add_balloon(x, y, z, color, model));
  }

  /** Adds a balloon of the first model resting on the floor at (x, z). */
  addBalloonOnFloor(x: number, z: number, color: number): void {
    this.call(() => this.e.add_balloon_on_floor(x, z, color));
  }

  /** Pops (removes) the body at dense index `index`; the last body takes its place. */
  remove(index: number): void {
    this.call(() => this.e.remove(index));
  }

  applyImpulse(index: number, impulse: number[], point: number[]): void {
    const [ix, iy, iz] = impulse;
    const [px, py, pz] = point;
    this.call(() => this.e.apply_impulse(index, ix, iy, iz, px, py, pz));
  }

  setVelocity(index: number, linear: number[], angular: number[]): void {
    const [vx, vy, vz] = linear;
    const [wx, wy, wz] = angular;
    this.call(() => this.e.set_velocity(index, vx, vy, vz, wx, wy, wz));
  }

  ribbonCount(): number {
    return this.e.ribbon_count();
  }

  /** Points of all ribbons together. */
  ribbonPointCount(): number {
    return this.e.ribbon_point_count();
  }

  /**
   * Every ribbon's points (`constants.ribbon_point_stride` floats each), ribbon
   * after ribbon, the knot first: a view, valid until the next call.
   */
  ribbonPoints(): Float32Array {
    const n = this.call(() => this.e.write_ribbon_points());
    return new Float32Array(this.memory.buffer, this.e.ribbon_points_ptr(), n);
  }

  /** Where each ribbon's points start, its balloon and its colour (copies). */
  ribbons(): RibbonTables {
    const n = this.call(() => this.e.write_ribbons());
    const buffer = this.memory.buffer;
    return {
      offsets: new Uint32Array(buffer, this.e.ribbon_offsets_ptr(), n + 1).slice(),
      bodies: new Uint32Array(buffer, this.e.ribbon_bodies_ptr(), n).slice(),
      colors: new Uint32Array(buffer, this.e.ribbon_colors_ptr(), n).slice(),
      weights: new Float32Array(buffer, this.e.ribbon_weights_ptr(), n).slice(),
    };
  }

  /**
   * Applies a live setting (a panel control that changes the running world:
   * the ribbon length, gravity, …) and writes it into the scene `sceneJson`
   * returns; refused outside `constants.live`'s range for it.
   */
  applyLive(setting: Glue.LiveSetting): void {
    this.call(() => this.e.apply_live(setting));
  }

  /** The first group's ribbon length, m (0: none), as the scene or `applyLive` set it. */
  ribbonLength(): number {
    return this.e.ribbon_length();
  }

  /** Holds point `point` of ribbon `ribbon` and pulls it toward (x, y, z); `dragTo` moves it, `release` lets go. */
  grabRibbon(ribbon: number, point: number, x: number, y: number, z: number): void {
    this.call(() => this.e.grab_ribbon(ribbon, point, x, y, z));
  }

  /** Holds the body at dense `index` by the world point (x, y, z) on it. */
  grab(index: number, x: number, y: number, z: number): void {
    this.call(() => this.e.grab(index, x, y, z));
  }

  /** Moves the grab target; the held point follows it. */
  dragTo(x: number, y: number, z: number): void {
    this.call(() => this.e.drag_to(x, y, z));
  }

  /** Lets go: the body keeps its velocity (a throw). */
  release(): void {
    this.call(() => this.e.release());
  }

  room(): RoomMesh {
    const nv = this.e.room_vertices_len();
    const nt = this.e.room_triangles_len();
    const buffer = this.memory.buffer;
    return {
      vertices: new Float32Array(buffer, this.e.room_vertices_ptr(), nv).slice(),
      triangles: new Uint32Array(buffer, this.e.room_triangles_ptr(), nt).slice(),
    };
  }

  furniture(): FurnitureMesh {
    return {
      vertices: this.call(() => this.e.furniture_vertices()),
      triangles: this.call(() => this.e.furniture_triangles()),
    };
  }

  modelCount(): number {
    return this.e.model_count();
  }

  /** The sphere tree of balloon model `model`, root first. */
  modelTree(model: number): TreeNode[] {
    const n = this.call(() => this.e.write_model_tree(model));
    const stride = this.constants.tree_stride;
    // Per node: cx, cy, cz, radius, depth, leaf (0/1).
    const f = new Float32Array(this.memory.buffer, this.e.tree_ptr(), n * stride);
    const nodes: TreeNode[] = [];
    for (let i = 0; i < n; i++) {
      const o = i * stride;
      nodes.push({ center: [f[o], f[o + 1], f[o + 2]], radius: f[o + 3], depth: f[o + 4], leaf: f[o + 5] > 0.5 });
    }
    return nodes;
  }

  /** The surface of balloon model `model`, copied out of wasm memory. */
  modelMesh(model: number): ModelMesh {
    const n = this.call(() => this.e.write_model_mesh(model));
    const floats = n * this.constants.mesh_vertex_stride;
    const buffer = this.memory.buffer;
    return {
      positions: new Float32Array(buffer, this.e.mesh_positions_ptr(), floats).slice(),
      normals: new Float32Array(buffer, this.e.mesh_normals_ptr(), floats).slice(),
      indices: new Uint32Array(buffer, this.e.mesh_indices_ptr(), this.e.mesh_index_len()).slice(),
    };
  }

  worldInfo(): Glue.WorldSummary {
    return this.call(() => this.e.world_info());
  }

  stats(): Glue.EngineStats {
    return this.call(() => this.e.stats());
  }

  /**
   * Times each thread's part of every stage from the next step on (`stats`'s
   * `threads`), or stops: two clock reads per task of a parallel pass while
   * on. For every engine of this module instance.
   */
  setThreadTiming(on: boolean): void {
    this.glue.set_thread_timing(on);
  }

  /** The last step's contacts, at most `max` of them (and at most `constants.max_contacts`). */
  contacts(max: number): Contacts {
    const count = this.call(() => this.e.write_contacts(max));
    const view = new Float32Array(this.memory.buffer, this.e.contacts_ptr(), count * this.constants.contact_stride);
    return { view, count, total: this.e.contact_total() };
  }

  /** The most contacts `contacts()` returns. */
  maxContacts(): number {
    return this.constants.max_contacts;
  }

  /** What the next steps record forces of: -1 nothing, -2 every body, else the body at that dense index. */
  setForceProbe(which: number): void {
    this.call(() => this.e.set_force_probe(which));
  }

  /**
   * The last step's recorded forces (`constants.force_floats` floats per
   * body, see forcesFrame.ts): a view, valid until the next call.
   */
  forces(): Float32Array {
    const n = this.call(() => this.e.write_forces());
    return new Float32Array(this.memory.buffer, this.e.forces_ptr(), n * this.constants.force_floats);
  }

  /** What the engine says of the body at dense `index` now: mass, gas, lift, motion. */
  bodyCard(index: number): Glue.BodyCard {
    return this.call(() => this.e.body_card(index));
  }

  /** Applies a command of the air tools (add a fan, set its speed, remove it, open the door) to the running world. */
  applyAir(command: Glue.AirCommand): void {
    this.call(() => this.e.apply_air(command));
  }

  /** Every air source (`constants.air.source_stride` floats each, sim/airLayout.ts): a view, valid until the next call. */
  airSources(): Float32Array {
    const n = this.call(() => this.e.write_air_sources());
    return new Float32Array(this.memory.buffer, this.e.air_sources_ptr(), n * this.constants.air.source_stride);
  }

  /** The air now on `nx`·`ny`·`nz` cells tiling the room: where, and the cells (a view, valid until the next call). */
  airGrid(nx: number, ny: number, nz: number): { grid: Glue.AirGrid; cells: Float32Array } {
    const grid = this.call(() => this.e.write_air_grid(nx, ny, nz));
    const cells = new Float32Array(this.memory.buffer, this.e.air_grid_ptr(), nx * ny * nz * this.constants.air.grid_stride);
    return { grid, cells };
  }

  /** The air's velocity now (m/s, x y z each) at `points` (m, x y z each): a view, valid until the next call. */
  airAt(points: Float32Array): Float32Array {
    const n = this.call(() => this.e.write_air_at(points));
    return new Float32Array(this.memory.buffer, this.e.air_points_ptr(), n * 3);
  }

  stateHash(): bigint {
    return this.e.state_hash();
  }

  /** Records the world now into the glTF export's ring (the last 10 s of simulated time). */
  recordExportFrame(): void {
    this.call(() => this.e.record_export_frame());
  }

  /** The ring's frames as an animated glTF binary (.glb), as `up export-gltf` writes one. */
  exportGltf(): Uint8Array {
    return this.call(() => this.e.export_gltf());
  }
}
