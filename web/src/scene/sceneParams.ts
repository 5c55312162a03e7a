// The panel's view of a scene: the handful of parameters a user tunes, read
// from and written back into the scene (JSON object of crates/up-scene).

import { engineConstants } from "./sceneSchema";

export interface PanelParams {
  /** Balloons over all groups. */
  count: number;
  /** Balloon size, inches (11 ≈ 0.28 m). */
  sizeIn: number;
  /** true: helium (rises); false: air (sinks). */
  helium: boolean;
  /** Length of the ribbon on each balloon, m (0: none): the first group's. */
  ribbonLength: number;
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

type Json = Record<string, unknown>;

const num = (v: unknown, fallback: number) => (typeof v === "number" && Number.isFinite(v) ? v : fallback);
const obj = (v: unknown): Json => (typeof v === "object" && v !== null && !Array.isArray(v) ? (v as Json) : {});

function groupsOf(scene: Json): Json[] {
  return Array.isArray(scene.balloons) ? (scene.balloons as unknown[]).map(obj) : [];
}

/** The engine's defaults for a scene (up-scene's, read from the module). */
function sceneDefaults(): { metresPerInch: number; diameter: number } {
  const c = engineConstants().scene;
  return { metresPerInch: c.metres_per_inch, diameter: c.default_diameter_m };
}

function diameterOf(group: Json): number {
  if (typeof group.diameter_m === "number") return group.diameter_m;
  if (typeof group.size_in === "number") return group.size_in * sceneDefaults().metresPerInch;
  return sceneDefaults().diameter;
}

export function paramsFromScene(scene: Json): PanelParams {
  const room = obj(scene.room);
  const sim = obj(scene.sim);
  const groups = groupsOf(scene);
  const first = groups[0] ?? {};
  return {
    count: groups.reduce((sum, g) => sum + num(g.count, 1), 0),
    sizeIn: Math.round((diameterOf(first) / sceneDefaults().metresPerInch) * 10) / 10,
    helium: first.gas !== "air",
    ribbonLength: num(obj(first.ribbon).length_m, 0),
    drag: num(sim.drag_coefficient, 0.95),
    restitution: num(sim.restitution, 0.4),
    friction: num(sim.friction, 0.5),
    substeps: num(sim.substeps, 4),
    width: num(room.width, 6),
    depth: num(room.depth, 6),
    wallHeight: num(room.wall_height, 3),
    ceiling: room.ceiling === "flat" ? "flat" : "pyramid",
    apexHeight: num(room.apex_height, 1.5),
  };
}

/** Splits `total` over `groups` as the CLI's `--balloons` does: the first ones get the remainder. */
export function splitCount(total: number, groups: number): number[] {
  const n = Math.max(1, groups);
  return Array.from({ length: n }, (_, i) => Math.floor(total / n) + (i < total % n ? 1 : 0));
}

/**
 * A copy of `scene` whose every group has ribbons of `length` m (0: none),
 * their other keys (segments, colour, weight) kept; a group without a ribbon
 * table stays without one at 0.
 */
export function withRibbonLength(scene: Json, length: number): Json {
  const out: Json = structuredClone(scene);
  const groups = groupsOf(out);
  for (const g of groups) {
    if (length > 0 || g.ribbon !== undefined) g.ribbon = { ...obj(g.ribbon), length_m: length };
  }
  if (groups.length > 0) out.balloons = groups;
  return out;
}

/** A copy of `scene` with the panel's parameters written in; other keys are kept. */
export function applyParams(scene: Json, p: PanelParams): Json {
  const out: Json = structuredClone(scene);
  const groups = groupsOf(out);
  if (groups.length === 0) groups.push({});
  const counts = splitCount(Math.max(0, Math.round(p.count)), groups.length);
  const diameter = Math.round(p.sizeIn * sceneDefaults().metresPerInch * 10000) / 10000;
  groups.forEach((g, i) => {
    g.count = counts[i];
    delete g.size_in;
    g.diameter_m = diameter;
    g.gas = p.helium ? "helium" : "air";
    // A spawn box sized for the old balloons or room may no longer fit: spread over the floor.
    delete g.spawn;
  });
  out.balloons = groups;
  const withRibbons = withRibbonLength(out, Math.max(0, p.ribbonLength));
  out.balloons = withRibbons.balloons;
  out.sim = { ...obj(out.sim), drag_coefficient: p.drag, restitution: p.restitution, friction: p.friction, substeps: Math.round(p.substeps) };
  out.room = { ...obj(out.room), width: p.width, depth: p.depth, wall_height: p.wallHeight, ceiling: p.ceiling, apex_height: p.apexHeight };
  return out;
}
