// The scene as the engine defines it. Its TypeScript types are written by
// tsify from up-scene's Rust structs into the module's .d.ts; its limits,
// defaults and colour names come from the module's `constants()` and its
// default scene (`default_scene_json()`). The page keeps no schema of its
// own: a scene is validated by asking the engine (`SimBridge.validate`, or
// the worker loading it), so the page accepts exactly what the engine
// accepts, with the engine's message otherwise.

import type { AirSpec, BalloonGroup, Constants, RoomSpec, Scene, SimSpec } from "../../public/wasm/up_wasm";

export type { AboutSpec, AirSpec, BalloonGroup, CeilingKind, GasKind, RoomSpec, Scene, SceneLimits, SimSpec, SpawnBox } from "../../public/wasm/up_wasm";

/**
 * A scene with every section's keys present, as the engine fills them in
 * (tsify types each key of a section with a serde default as optional).
 */
export interface FilledScene extends Scene {
  room: Required<Omit<RoomSpec, "mesh">> & Pick<RoomSpec, "mesh">;
  balloons: BalloonGroup[];
  air: AirSpec;
  sim: Required<SimSpec>;
}

let current: { constants: Constants; defaults: FilledScene } | null = null;

/** Records the engine's constants and default scene once it has started (the bridge does, on its first world). */
export function setEngineConstants(constants: Constants, defaultSceneJson: string): void {
  // The engine writes every default out: its default scene is filled.
  current = { constants, defaults: JSON.parse(defaultSceneJson) as FilledScene };
}

function started(): { constants: Constants; defaults: FilledScene } {
  if (!current) throw new Error("the engine's constants are read when it starts, and it has not started yet");
  return current;
}

/** The engine's constants; throws before the engine has started. */
export function engineConstants(): Constants {
  return started().constants;
}

/**
 * `scene` with each missing key read as the engine reads it: from its
 * default scene (a missing section is the default's, a missing key of a
 * section the default's key). Throws before the engine has started.
 */
export function filledScene(scene: Scene): FilledScene {
  const d = started().defaults;
  return {
    ...scene,
    room: { ...d.room, ...scene.room },
    balloons: scene.balloons ?? d.balloons,
    air: { ...d.air, ...scene.air },
    sim: { ...d.sim, ...scene.sim },
  };
}
