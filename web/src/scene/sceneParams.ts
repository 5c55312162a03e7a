// The panel's view of a scene: the handful of parameters a user tunes that
// need a new world (the room, the balloons, the solver), read from and
// written back into the scene. Missing keys read as the engine reads them
// (its default scene); live settings (the ribbon length, gravity) are not
// here: they change the running world (ui/panel.ts's live lines).

import { engineConstants, filledScene, type Scene } from "./sceneSchema";
import type { BalloonGroup } from "./sceneSchema";

export interface PanelParams {
  /** Balloons over all groups. */
  count: number;
  /** Balloon size, inches (11 ≈ 0.28 m). */
  sizeIn: number;
  /** true: helium (rises); false: air (sinks). */
  helium: boolean;
  /** Drag coefficient C_D. */
  drag: number;
  restitution: number;
  friction: number;
  substeps: number;
  /** m */
  width: number;
  /** m */
  depth: number;
  /** m */
  wallHeight: number;
  ceiling: "pyramid" | "flat";
  /** m above the walls. */
  apexHeight: number;
}

/** A group's diameter, m, as the engine reads it (`BalloonGroup::diameter`, latex default). */
function diameterOf(group: BalloonGroup | undefined): number {
  const c = engineConstants().scene;
  if (group?.diameter_m !== undefined) return group.diameter_m;
  if (group?.size_in !== undefined) return group.size_in * c.metres_per_inch;
  return c.default_diameter_m;
}

export function paramsFromScene(scene: Scene): PanelParams {
  const { room, sim, balloons } = filledScene(scene);
  const first = balloons[0];
  return {
    // A group without a count is one balloon (up-scene's `BalloonGroup::default`).
    count: balloons.reduce((sum, g) => sum + (g.count ?? 1), 0),
    sizeIn: Math.round((diameterOf(first) / engineConstants().scene.metres_per_inch) * 10) / 10,
    helium: first?.gas !== "air",
    drag: sim.drag_coefficient,
    restitution: sim.restitution,
    friction: sim.friction,
    substeps: sim.substeps,
    width: room.width,
    depth: room.depth,
    wallHeight: room.wall_height,
    ceiling: room.ceiling,
    apexHeight: room.apex_height,
  };
}

/** Splits `total` over `groups` as the CLI's `--balloons` does: the first ones get the remainder. */
export function splitCount(total: number, groups: number): number[] {
  const n = Math.max(1, groups);
  return Array.from({ length: n }, (_, i) => Math.floor(total / n) + (i < total % n ? 1 : 0));
}

/** A copy of `scene` with the panel's parameters written in; other keys are kept. */
export function applyParams(scene: Scene, p: PanelParams): Scene {
  const out: Scene = structuredClone(scene);
  const groups: BalloonGroup[] = out.balloons ?? [];
  if (groups.length === 0) groups.push({});
  const counts = splitCount(Math.max(0, Math.round(p.count)), groups.length);
  const diameter = Math.round(p.sizeIn * engineConstants().scene.metres_per_inch * 10000) / 10000;
  groups.forEach((g, i) => {
    g.count = counts[i];
    delete g.size_in;
    g.diameter_m = diameter;
    g.gas = p.helium ? "helium" : "air";
    // A spawn box sized for the old balloons or room may no longer fit: spread over the floor.
    delete g.spawn;
  });
  out.balloons = groups;
  out.sim = { ...out.sim, drag_coefficient: p.drag, restitution: p.restitution, friction: p.friction, substeps: Math.round(p.substeps) };
  out.room = { ...out.room, width: p.width, depth: p.depth, wall_height: p.wallHeight, ceiling: p.ceiling, apex_height: p.apexHeight };
  return out;
}
