// The scene as the engine defines it. Its TypeScript types are written by
// tsify from up-scene's Rust structs into the module's .d.ts; its limits,
// defaults and colour names come from the module's `constants()`. The page
// keeps no schema of its own: a scene is validated by asking the engine
// (`SimBridge.validate`, or the worker loading it), so the page accepts
// exactly what the engine accepts, with the engine's message otherwise.

import type { Constants } from "../sim/engine";

export type { AirSpec, BalloonGroup, CeilingKind, GasKind, RoomSpec, Scene, SceneLimits, SimSpec, SpawnBox } from "../../public/wasm/up_wasm";

let current: Constants | null = null;

/** Records the engine's constants once it has started (the bridge does, on its first world). */
export function setEngineConstants(constants: Constants): void {
  current = constants;
}

/** The engine's constants; throws before the engine has started. */
export function engineConstants(): Constants {
  if (!current) throw new Error("the engine's constants are read when it starts, and it has not started yet");
  return current;
}
