// Messages between the main thread and the physics worker.
//
// Poses travel in ping-pong buffers: the worker fills a buffer it owns and
// transfers it; the main thread keeps the newest frame and hands the previous
// buffer back. No typed array is allocated per frame on either side.

import type { AirCommand, Constants, EngineStats, Finish, FurnitureMesh, LiveSetting, ModelMesh, RibbonTables, RoomMesh, TreeNode } from "./engine";
import type { FloatSample } from "../ui/floatPlot";
import type { ForcesPayload } from "./forcesFrame";
import type { StepsMeasured } from "./stepMeter";
import type { PoolSettings } from "./threadPool";
import type { AirField } from "./airLayout";

export type Vec3Tuple = [number, number, number];

export type ToWorker =
  /** `wasmUrl`: the single-threaded module; the worker runs the threaded one next to it when it can and `threads` > 1. */
  | { type: "init"; wasmUrl: string; sceneJson: string | null; threads: number; pool: PoolSettings }
  | { type: "load"; sceneJson: string | null }
  /** Builds the world from a scene file in TOML (the teaching scenes). */
  | { type: "loadToml"; sceneToml: string }
  /** Selects body `index` of frame `version` (its forces and card travel in the frames); -1: none. */
  | { type: "select"; index: number; version: number }
  /** Every balloon's forces in the frames, or only the selected one's. */
  | { type: "forcesOnAll"; on: boolean }
  | { type: "pause"; paused: boolean }
  | { type: "step" }
  /** Time-lapse: simulated seconds per real second (1: real time, fixed steps; more: `Engine.advance`). */
  | { type: "rate"; rate: number }
  /** Debug view on or off: contacts travel in the frames only while it is on. */
  | { type: "debug"; on: boolean }
  | { type: "addOnFloor"; x: number; z: number }
  | { type: "pop"; index: number; version: number }
  | { type: "grab"; index: number; version: number; point: Vec3Tuple }
  /** Holds point `point` of ribbon `ribbon` (ribbon order of frame `version`) and pulls it toward `target`. */
  | { type: "grabRibbon"; ribbon: number; point: number; version: number; target: Vec3Tuple }
  /** A live setting for the running world (`Engine.applyLive`), as the panel made it; answered by `scene`. */
  | { type: "live"; setting: LiveSetting }
  | { type: "dragTo"; point: Vec3Tuple }
  | { type: "release" }
  | { type: "return"; buffer: ArrayBuffer }
  /** Asks the engine whether it would load `sceneJson`; answered by `validated` with the same `id`. */
  | { type: "validate"; id: number; sceneJson: string }
  /** Whether the page draws its frames (it does unless they are held): the pool spins only where it leaves the drawing a core (threadPool.ts). */
  | { type: "drawing"; on: boolean }
  /** Measurements: the scene from its start, `steps` steps timed one by one (sim/stepMeter.ts); `threadTimes`: each thread's part of each stage too. */
  | { type: "measureSteps"; steps: number; threadTimes: boolean }
  /** Asks for the world's state hash and the steps taken since it was built; answered by `hash` with the same `id`. */
  | { type: "hash"; id: number }
  /** Asks for the last 10 s of frames sent, as a .glb; answered by `gltf` with the same `id`. */
  | { type: "exportGltf"; id: number }
  /** A command of the air tools for the running world (`Engine.applyAir`), as the panel made it. */
  | { type: "air"; command: AirCommand }
  /** "Show air" on or off: the sampled field comes (`airField`) only while it is on. */
  | { type: "showAir"; on: boolean };

/** What the main thread needs to draw a freshly built world. */
export interface WorldInfo {
  /** The scene as the engine read it, every default written out. */
  sceneJson: string;
  defaultSceneJson: string;
  room: RoomMesh;
  /** The tables, chairs and meshes standing in the room. */
  furniture: FurnitureMesh;
  /** Sphere tree of each balloon model, root first (debug view, picking). */
  trees: TreeNode[][];
  /** Linear RGB 0–1 of each colour index. */
  palette: Vec3Tuple[];
  /** Names of the colours (`red`, `#10a0ff`), by colour index. */
  colorNames: string[];
  /** Diameter of each balloon model, m. */
  diameters: number[];
  /** Each foil model's surface (drawn instead of the latex OBJ); null for a latex model. */
  foilMeshes: (ModelMesh | null)[];
  /** How each balloon model is drawn: the scene's `finish`, or its kind's. */
  finishes: Finish[];
  /** s per step. */
  dt: number;
  capacity: number;
  /** The engine's constants (strides, limits, colours, error kinds). */
  constants: Constants;
  /** Threads that step the engine. */
  threads: number;
  /** Whether the page is cross-origin isolated (else the engine runs on one thread). */
  isolated: boolean;
}

export interface Frame {
  type: "frame";
  /** `[previous poses | current poses | contacts | previous ribbons | current ribbons]`: see sim/frameLayout.ts. */
  buffer: ArrayBuffer;
  count: number;
  /** Floats of ribbon points in each of the two ribbon parts. */
  ribbonFloats: number;
  /** Contacts in the buffer (0 unless the debug view is on). */
  contactCount: number;
  /** Contacts the step had in all, written or not (0 unless the debug view is on). */
  contactTotal: number;
  /** Changes whenever bodies or ribbons are added or removed (dense order may change). */
  version: number;
  /** Colour and model index per body; sent only when `version` changed. */
  colors?: Uint32Array;
  models?: Uint32Array;
  /** Each ribbon's first point, balloon and colour; sent only when `version` changed. */
  ribbons?: RibbonTables;
  /** Absolute time (timeOrigin + now) the current step was taken, ms. */
  stepTime: number;
  /** Simulated seconds since the world was built. */
  simTime: number;
  steps: number;
  paused: boolean;
  /** The room's air temperature now, °C. */
  airTemperatureC: number;
  /** The time-lapse rate asked for, and the one the clock achieved over the last second or so. */
  rate: number;
  achievedRate: number;
  /** The probed forces and the selected body's card; only while a body is selected or all are shown. */
  forces?: ForcesPayload;
  /** The air's sources now (sim/airLayout.ts); only while the room has any. */
  airSources?: Float32Array;
}

/** Where the balloons floated at simulated time `t` (shares of all balloons), and their mean lift left (0–1). */
export interface CensusSample extends FloatSample {
  meanLiftFraction: number;
}

export type FromWorker =
  | { type: "ready"; info: WorldInfo }
  | Frame
  | { type: "stats"; stats: EngineStats; stepsPerSecond: number }
  /** A look at where the balloons float, every simulated second to minute (`censusInterval`). */
  | { type: "census"; sample: CensusSample }
  | { type: "error"; message: string; fatal: boolean }
  /** The scene as the engine holds it after a live setting (every default written out). */
  | { type: "scene"; sceneJson: string }
  /** The engine's message when it refuses the scene of `validate` request `id`, else null. */
  | { type: "validated"; id: number; error: string | null }
  | ({ type: "stepsMeasured" } & StepsMeasured)
  /** The world's state hash (16 hex digits, as the `up` CLI prints it) after `steps` steps. */
  | { type: "hash"; id: number; hash: string; steps: number }
  /** The .glb of `exportGltf` request `id`, or why there is none. */
  | { type: "gltf"; id: number; glb: ArrayBuffer | null; error: string | null }
  /** The air sampled on a grid of the room, every quarter second or so while "show air" is on. */
  | { type: "airField"; field: AirField };
