// Typed wrapper over the up-wasm exports: plain `extern "C"` functions over a
// world that lives inside the module. Every fallible export returns a status
// code; this wrapper turns a non-zero code into an `EngineError` carrying the
// module's own message. Bulk data (poses, colours, the room) are read as views
// of wasm memory, re-created whenever memory grows.

/** Status codes of up-wasm (crates/up-wasm/src/status.rs). */
export const Status = {
  Ok: 0,
  NoWorld: 1,
  BadArgument: 2,
  OutOfRange: 3,
  Full: 4,
  Scene: 5,
  Physics: 6,
  Encoding: 7,
  Alloc: 8,
} as const;

const STATUS_NAMES: Record<number, string> = Object.fromEntries(
  Object.entries(Status).map(([name, code]) => [code, name]),
);

export class EngineError extends Error {
  constructor(
    readonly code: number,
    message: string,
  ) {
    super(message);
    this.name = `EngineError(${STATUS_NAMES[code] ?? code})`;
  }
}

/** The raw exports, as declared in crates/up-wasm/src/lib.rs. */
interface Exports {
  memory: WebAssembly.Memory;
  up_alloc(len: number): number;
  up_free(ptr: number, len: number): number;
  up_last_error_ptr(): number;
  up_last_error_len(): number;
  up_output_ptr(): number;
  up_output_len(): number;
  up_world_from_json(ptr: number, len: number): number;
  up_world_from_toml(ptr: number, len: number): number;
  up_world_default(): number;
  up_scene_json(): number;
  up_default_scene_json(): number;
  up_step(n: number): number;
  up_body_count(): number;
  up_capacity(): number;
  up_write_poses(): number;
  up_poses_ptr(): number;
  up_write_colors(): number;
  up_colors_ptr(): number;
  up_write_models(): number;
  up_models_ptr(): number;
  up_add_balloon(x: number, y: number, z: number, color: number, model: number): number;
  up_add_balloon_on_floor(x: number, z: number, color: number): number;
  up_remove(index: number): number;
  up_apply_impulse(index: number, ix: number, iy: number, iz: number, px: number, py: number, pz: number): number;
  up_set_velocity(index: number, vx: number, vy: number, vz: number, wx: number, wy: number, wz: number): number;
  up_grab(index: number, x: number, y: number, z: number): number;
  up_drag_to(x: number, y: number, z: number): number;
  up_release(): number;
  up_room_vertex_count(): number;
  up_room_vertices_ptr(): number;
  up_room_triangle_count(): number;
  up_room_triangles_ptr(): number;
  up_model_count(): number;
  up_model_tree(model: number): number;
  up_tree_ptr(): number;
  up_tree_node_count(): number;
  up_stats_json(): number;
  up_world_info_json(): number;
  up_state_hash(): bigint;
  up_write_contacts(max: number): number;
  up_contacts_ptr(): number;
  up_contact_count(): number;
  up_contact_total(): number;
  up_max_contacts(): number;
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

/** What a built world holds besides its bodies. */
export interface WorldSummary {
  /** Linear RGB 0–1 of each colour index. */
  colors: [number, number, number][];
  /** Names of the colours as written in the scene (`red`, `#10a0ff`). */
  color_names: string[];
  /** Diameter of each balloon model, m. */
  diameters: number[];
  /** s per step. */
  dt: number;
}

export interface EngineStats {
  /** Stage name to milliseconds for the last step, in step order ("total" last). */
  stages: [string, number][];
  bodies: number;
  awake: number;
  pairs: number;
  contacts: number;
  /** m */
  max_penetration: number;
}

/** Floats per pose: x, y, z, qx, qy, qz, qw of the balloon's mesh frame. */
export const POSE_FLOATS = 7;

/** The last step's contacts, as `up_write_contacts` wrote them. */
export interface Contacts {
  /** CONTACT_STRIDE floats per contact (sim/frameLayout.ts): a view, valid until the next call. */
  view: Float32Array;
  /** Contacts in `view`. */
  count: number;
  /** Contacts the step had in all (more than `count` when capped). */
  total: number;
}

export class Engine {
  private constructor(private readonly x: Exports) {}

  /** Instantiates the module from its bytes; `now` is the stage-timer clock (ms). */
  static async load(bytes: BufferSource, now: () => number = () => performance.now()): Promise<Engine> {
    const imports = { env: { up_now_ms: now } };
    const { instance } = await WebAssembly.instantiate(bytes, imports);
    return new Engine(instance.exports as unknown as Exports);
  }

  /** Fetches the module's bytes at `url` (instantiate them with `load`, again after a trap). */
  static async fetchBytes(url: string): Promise<ArrayBuffer> {
    const response = await fetch(url);
    if (!response.ok) throw new Error(`cannot load the physics engine ${url}: HTTP ${response.status}`);
    return response.arrayBuffer();
  }

  /** Fetches and instantiates the module at `url`. */
  static async fetch(url: string): Promise<Engine> {
    return Engine.load(await Engine.fetchBytes(url));
  }

  private check(code: number): void {
    if (code === Status.Ok) return;
    const ptr = this.x.up_last_error_ptr();
    const len = this.x.up_last_error_len();
    const message = new TextDecoder().decode(new Uint8Array(this.x.memory.buffer, ptr, len));
    throw new EngineError(code, message || `up-wasm status ${code}`);
  }

  private output(): string {
    const ptr = this.x.up_output_ptr();
    const len = this.x.up_output_len();
    return new TextDecoder().decode(new Uint8Array(this.x.memory.buffer, ptr, len));
  }

  /** Copies `text` into a fresh wasm buffer, calls `f(ptr, len)`, frees the buffer. */
  private withString(text: string, f: (ptr: number, len: number) => number): void {
    const bytes = new TextEncoder().encode(text);
    const len = Math.max(1, bytes.length);
    const ptr = this.x.up_alloc(len);
    if (ptr === 0) throw new EngineError(Status.Alloc, `cannot allocate ${len} bytes for the scene`);
    try {
      new Uint8Array(this.x.memory.buffer, ptr, bytes.length).set(bytes);
      this.check(f(ptr, bytes.length));
    } finally {
      this.x.up_free(ptr, len);
    }
  }

  /** Builds the world from a scene in JSON (the web app's own format). */
  loadSceneJson(json: string): void {
    this.withString(json, (p, n) => this.x.up_world_from_json(p, n));
  }

  /** Builds the world from a scene in TOML (the CLI's files). */
  loadSceneToml(toml: string): void {
    this.withString(toml, (p, n) => this.x.up_world_from_toml(p, n));
  }

  /** Builds the default scene: the original UP room. */
  loadDefaultScene(): void {
    this.check(this.x.up_world_default());
  }

  /** The loaded scene, as JSON with every default written out. */
  sceneJson(): string {
    this.check(this.x.up_scene_json());
    return this.output();
  }

  /** The default scene as JSON. Needs no world. */
  defaultSceneJson(): string {
    this.check(this.x.up_default_scene_json());
    return this.output();
  }

  step(n = 1): void {
    this.check(this.x.up_step(n));
  }

  bodyCount(): number {
    return this.x.up_body_count();
  }

  /** Most bodies the world accepts. */
  capacity(): number {
    return this.x.up_capacity();
  }

  /**
   * Poses of all bodies, dense order: a view of wasm memory, valid until the
   * next call into the engine.
   */
  poses(): Float32Array {
    this.check(this.x.up_write_poses());
    return new Float32Array(this.x.memory.buffer, this.x.up_poses_ptr(), this.bodyCount() * POSE_FLOATS);
  }

  /** Colour index of every body, dense order (a view, valid until the next call). */
  colors(): Uint32Array {
    this.check(this.x.up_write_colors());
    return new Uint32Array(this.x.memory.buffer, this.x.up_colors_ptr(), this.bodyCount());
  }

  /** Balloon model index of every body, dense order (a view, valid until the next call). */
  models(): Uint32Array {
    this.check(this.x.up_write_models());
    return new Uint32Array(this.x.memory.buffer, this.x.up_models_ptr(), this.bodyCount());
  }

  addBalloon(x: number, y: number, z: number, color: number, model = 0): void {
    this.check(this.x.up_add_balloon(x, y, z, color, model));
  }

  /** Adds a balloon of the first model resting on the floor at (x, z). */
  addBalloonOnFloor(x: number, z: number, color: number): void {
    this.check(this.x.up_add_balloon_on_floor(x, z, color));
  }

  /** Pops (removes) the body at dense index `index`; the last body takes its place. */
  remove(index: number): void {
    this.check(this.x.up_remove(index));
  }

  applyImpulse(index: number, impulse: number[], point: number[]): void {
    const [ix, iy, iz] = impulse;
    const [px, py, pz] = point;
    this.check(this.x.up_apply_impulse(index, ix, iy, iz, px, py, pz));
  }

  setVelocity(index: number, linear: number[], angular: number[]): void {
    const [vx, vy, vz] = linear;
    const [wx, wy, wz] = angular;
    this.check(this.x.up_set_velocity(index, vx, vy, vz, wx, wy, wz));
  }

  /** Holds the body at dense `index` by the world point (x, y, z) on it. */
  grab(index: number, x: number, y: number, z: number): void {
    this.check(this.x.up_grab(index, x, y, z));
  }

  /** Moves the grab target; the held point follows it. */
  dragTo(x: number, y: number, z: number): void {
    this.check(this.x.up_drag_to(x, y, z));
  }

  /** Lets go: the body keeps its velocity (a throw). */
  release(): void {
    this.check(this.x.up_release());
  }

  room(): RoomMesh {
    const nv = this.x.up_room_vertex_count();
    const nt = this.x.up_room_triangle_count();
    const buffer = this.x.memory.buffer;
    return {
      vertices: new Float32Array(buffer, this.x.up_room_vertices_ptr(), nv * 3).slice(),
      triangles: new Uint32Array(buffer, this.x.up_room_triangles_ptr(), nt * 3).slice(),
    };
  }

  modelCount(): number {
    return this.x.up_model_count();
  }

  /** The sphere tree of balloon model `model`, root first. */
  modelTree(model: number): TreeNode[] {
    this.check(this.x.up_model_tree(model));
    const n = this.x.up_tree_node_count();
    // Per node: cx, cy, cz, radius, depth, leaf (0/1).
    const f = new Float32Array(this.x.memory.buffer, this.x.up_tree_ptr(), n * 6);
    const nodes: TreeNode[] = [];
    for (let i = 0; i < n; i++) {
      const o = i * 6;
      nodes.push({ center: [f[o], f[o + 1], f[o + 2]], radius: f[o + 3], depth: f[o + 4], leaf: f[o + 5] > 0.5 });
    }
    return nodes;
  }

  worldInfo(): WorldSummary {
    this.check(this.x.up_world_info_json());
    return JSON.parse(this.output()) as WorldSummary;
  }

  stats(): EngineStats {
    this.check(this.x.up_stats_json());
    return JSON.parse(this.output()) as EngineStats;
  }

  /** The last step's contacts, at most `max` of them (and at most `maxContacts()`). */
  contacts(max: number): Contacts {
    this.check(this.x.up_write_contacts(max));
    const count = this.x.up_contact_count();
    // 8 floats per contact: crates/up-wasm/src/contacts.rs.
    const view = new Float32Array(this.x.memory.buffer, this.x.up_contacts_ptr(), count * 8);
    return { view, count, total: this.x.up_contact_total() };
  }

  /** The most contacts `contacts()` returns. */
  maxContacts(): number {
    return this.x.up_max_contacts();
  }

  stateHash(): bigint {
    return this.x.up_state_hash();
  }
}
