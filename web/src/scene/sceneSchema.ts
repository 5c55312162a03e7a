// The scene schema of crates/up-scene (src/scene.rs, src/scene_validate.rs),
// checked in TypeScript so that a shared link is validated before it reaches
// the engine, with messages that name the key and the expected value. The
// engine validates again when it builds the world; this is the first gate.

export interface SceneProblem {
  /** Key path, such as `room.width` or `balloons[0].colors[2]`. */
  key: string;
  message: string;
}

export const MAX_TOTAL_BALLOONS = 200_000;
/** Balloon groups a scene may have, and colours a group may list (up_scene: MAX_BALLOON_GROUPS, MAX_GROUP_COLORS). */
export const MAX_BALLOON_GROUPS = 64;
export const MAX_GROUP_COLORS = 64;
export const MIN_ROOM_SIZE_M = 0.5;
export const MAX_ROOM_SIZE_M = 1000;
export const MIN_BALLOON_DIAMETER_M = 0.05;
export const MAX_BALLOON_DIAMETER_M = 5;
export const METRES_PER_INCH = 0.0254;
export const DEFAULT_DIAMETER_M = 0.28;
export const MAX_SEED = 2 ** 53 - 1;

/** Colour names the engine knows (crates/up-scene/src/obj.rs). */
export const COLOR_NAMES = ["red", "yellow", "blue", "green", "purple", "orange", "pink", "white", "black", "cyan", "magenta", "gold", "silver"];

type Obj = Record<string, unknown>;

const isObject = (v: unknown): v is Obj => typeof v === "object" && v !== null && !Array.isArray(v);

class Checker {
  readonly problems: SceneProblem[] = [];

  fail(key: string, message: string): void {
    this.problems.push({ key, message });
  }

  /** A table with only `allowed` keys; returns it, or `null` when absent or wrong. */
  table(parent: Obj, key: string, path: string, allowed: string[]): Obj | null {
    if (!(key in parent)) return null;
    const v = parent[key];
    if (!isObject(v)) {
      this.fail(path, `expected a table (JSON object), found ${kind(v)}`);
      return null;
    }
    this.unknownKeys(v, path, allowed);
    return v;
  }

  unknownKeys(v: Obj, path: string, allowed: string[]): void {
    for (const k of Object.keys(v)) {
      if (!allowed.includes(k)) {
        const where = path ? `${path}.${k}` : k;
        this.fail(where, `unknown key, expected one of ${allowed.join(", ")}`);
      }
    }
  }

  /** A number in [lo, hi] (or (lo, hi] when `loOpen`), when present. */
  number(t: Obj, key: string, path: string, lo: number, hi: number, loOpen = false, unit = ""): number | undefined {
    if (!(key in t)) return undefined;
    const v = t[key];
    const where = `${path}.${key}`;
    const range = `${loOpen ? "(" : "["}${lo}, ${hi}]${unit ? " " + unit : ""}`;
    if (typeof v !== "number" || !Number.isFinite(v)) {
      this.fail(where, `expected a finite number in ${range}, found ${kind(v)}`);
      return undefined;
    }
    if ((loOpen ? v <= lo : v < lo) || v > hi) {
      this.fail(where, `expected a finite number in ${range}, found ${v}`);
      return undefined;
    }
    return v;
  }

  integer(t: Obj, key: string, path: string, lo: number, hi: number): number | undefined {
    if (!(key in t)) return undefined;
    const v = t[key];
    const where = `${path}.${key}`;
    if (typeof v !== "number" || !Number.isInteger(v) || v < lo || v > hi) {
      this.fail(where, `expected an integer in [${lo}, ${hi}], found ${typeof v === "number" ? v : kind(v)}`);
      return undefined;
    }
    return v;
  }

  boolean(t: Obj, key: string, path: string): void {
    if (key in t && typeof t[key] !== "boolean") this.fail(`${path}.${key}`, `expected true or false, found ${kind(t[key])}`);
  }

  oneOf(t: Obj, key: string, path: string, options: string[]): string | undefined {
    if (!(key in t)) return undefined;
    const v = t[key];
    if (typeof v !== "string" || !options.includes(v)) {
      this.fail(`${path}.${key}`, `expected one of ${options.map((o) => `"${o}"`).join(", ")}, found ${JSON.stringify(v)}`);
      return undefined;
    }
    return v;
  }

  /** A finite [x, y, z], each within ±`each`, no longer than `maxLen`. */
  vector(t: Obj, key: string, path: string, each: number, maxLen: number, unit: string): number[] | undefined {
    if (!(key in t)) return undefined;
    const v = t[key];
    const where = `${path}.${key}`;
    if (!Array.isArray(v) || v.length !== 3 || !v.every((c) => typeof c === "number" && Number.isFinite(c))) {
      this.fail(where, `expected finite [x, y, z] in ${unit}, found ${JSON.stringify(v)}`);
      return undefined;
    }
    const out = v as number[];
    if (out.some((c) => Math.abs(c) > each) || Math.hypot(out[0], out[1], out[2]) > maxLen) {
      this.fail(where, `expected [x, y, z] no longer than ${maxLen} ${unit}, found ${JSON.stringify(v)}`);
      return undefined;
    }
    return out;
  }
}

function kind(v: unknown): string {
  if (v === null) return "null";
  if (Array.isArray(v)) return "an array";
  if (typeof v === "string") return `the text ${JSON.stringify(v.length > 40 ? v.slice(0, 40) + "…" : v)}`;
  return `a ${typeof v}`;
}

export function isColor(name: string): boolean {
  return /^#[0-9a-fA-F]{6}$/.test(name) || COLOR_NAMES.includes(name.toLowerCase());
}

/** Every problem found in `scene` (empty when it is valid). */
export function validateScene(scene: unknown): SceneProblem[] {
  const c = new Checker();
  if (!isObject(scene)) {
    c.fail("(scene)", `expected a JSON object with room, balloons, air and sim, found ${kind(scene)}`);
    return c.problems;
  }
  c.unknownKeys(scene, "", ["room", "balloons", "air", "sim"]);

  const room = c.table(scene, "room", "room", ["width", "depth", "wall_height", "ceiling", "apex_height", "mesh"]);
  let width = 6;
  let depth = 6;
  let wallHeight = 3;
  let top = 4.5;
  if (room) {
    if ("mesh" in room) c.fail("room.mesh", "a mesh room cannot be loaded in the browser: expected a box room (leave mesh out)");
    width = c.number(room, "width", "room", MIN_ROOM_SIZE_M, MAX_ROOM_SIZE_M, false, "m") ?? width;
    depth = c.number(room, "depth", "room", MIN_ROOM_SIZE_M, MAX_ROOM_SIZE_M, false, "m") ?? depth;
    wallHeight = c.number(room, "wall_height", "room", MIN_ROOM_SIZE_M, MAX_ROOM_SIZE_M, false, "m") ?? wallHeight;
    const ceiling = c.oneOf(room, "ceiling", "room", ["pyramid", "flat"]) ?? "pyramid";
    const apex = c.number(room, "apex_height", "room", 0, MAX_ROOM_SIZE_M, true, "m") ?? 1.5;
    top = ceiling === "pyramid" ? wallHeight + apex : wallHeight;
  }

  const air = c.table(scene, "air", "air", ["temperature_c", "pressure_kpa"]);
  if (air) {
    c.number(air, "temperature_c", "air", -60, 60, false, "°C");
    c.number(air, "pressure_kpa", "air", 50, 150, false, "kPa");
  }

  const sim = c.table(scene, "sim", "sim", [
    "seed", "dt", "substeps", "duration_s", "gravity", "friction", "restitution", "drag_coefficient",
    "added_mass_coefficient", "angular_damping", "contact_hertz", "contact_damping_ratio", "sleep", "continuous",
  ]);
  if (sim) {
    c.integer(sim, "seed", "sim", 0, MAX_SEED);
    c.number(sim, "dt", "sim", 0, 0.1, true, "s");
    c.integer(sim, "substeps", "sim", 1, 64);
    c.number(sim, "duration_s", "sim", 0, 86_400, true, "s");
    c.vector(sim, "gravity", "sim", 1000, Infinity, "m/s²");
    c.number(sim, "friction", "sim", 0, 10);
    c.number(sim, "restitution", "sim", 0, 1);
    c.number(sim, "drag_coefficient", "sim", 0, 10);
    c.number(sim, "added_mass_coefficient", "sim", 0, 10);
    c.number(sim, "angular_damping", "sim", 0, 1000, false, "1/s");
    c.number(sim, "contact_hertz", "sim", 0, 10_000, true, "Hz");
    c.number(sim, "contact_damping_ratio", "sim", 0, 1000);
    c.boolean(sim, "sleep", "sim");
    c.boolean(sim, "continuous", "sim");
  }

  if ("balloons" in scene) {
    const groups = scene.balloons;
    if (!Array.isArray(groups)) {
      c.fail("balloons", `expected an array of balloon groups, found ${kind(groups)}`);
    } else {
      if (groups.length > MAX_BALLOON_GROUPS) c.fail("balloons", `expected at most ${MAX_BALLOON_GROUPS} balloon groups, found ${groups.length}`);
      let total = 0;
      groups.forEach((g, i) => {
        const path = `balloons[${i}]`;
        if (!isObject(g)) {
          c.fail(path, `expected a table (JSON object), found ${kind(g)}`);
          return;
        }
        c.unknownKeys(g, path, [
          "count", "colors", "diameter_m", "size_in", "gas", "envelope_mass_g", "knot_mass_g", "spawn",
          "velocity", "angular_velocity", "tilt_deg", "yaw_deg", "leaves",
        ]);
        const count = c.integer(g, "count", path, 0, MAX_TOTAL_BALLOONS) ?? 1;
        total += count;
        if (total > MAX_TOTAL_BALLOONS) c.fail(`${path}.count`, `expected at most ${MAX_TOTAL_BALLOONS} balloons over all groups, found ${total} so far`);
        if ("colors" in g) {
          const colors = g.colors;
          if (!Array.isArray(colors) || colors.length === 0) {
            c.fail(`${path}.colors`, `expected a non-empty list of colours, found ${kind(colors)}`);
          } else if (colors.length > MAX_GROUP_COLORS) {
            c.fail(`${path}.colors`, `expected at most ${MAX_GROUP_COLORS} colours, found ${colors.length}`);
          } else {
            colors.forEach((col, j) => {
              if (typeof col !== "string" || !isColor(col)) {
                c.fail(`${path}.colors[${j}]`, `expected a colour name (${COLOR_NAMES.slice(0, 6).join(", ")}, ...) or "#rrggbb", found ${JSON.stringify(col)}`);
              }
            });
          }
        }
        if ("diameter_m" in g && "size_in" in g) c.fail(`${path}.size_in`, "expected either diameter_m or size_in, not both");
        const d =
          c.number(g, "diameter_m", path, MIN_BALLOON_DIAMETER_M, MAX_BALLOON_DIAMETER_M, false, "m") ??
          (() => {
            const inches = c.number(g, "size_in", path, Math.ceil(MIN_BALLOON_DIAMETER_M / METRES_PER_INCH), Math.floor(MAX_BALLOON_DIAMETER_M / METRES_PER_INCH), false, "in");
            return inches === undefined ? DEFAULT_DIAMETER_M : inches * METRES_PER_INCH;
          })();
        c.oneOf(g, "gas", path, ["helium", "air"]);
        c.number(g, "envelope_mass_g", path, 0.01, 10_000, false, "g");
        c.number(g, "knot_mass_g", path, 0, 1000, false, "g");
        c.vector(g, "velocity", path, Infinity, 343, "m/s");
        c.vector(g, "angular_velocity", path, Infinity, 1000, "rad/s");
        c.number(g, "tilt_deg", path, 0, 90, false, "°");
        c.number(g, "yaw_deg", path, 0, 180, false, "°");
        c.integer(g, "leaves", path, 1, 32);
        const smallest = Math.min(width, depth, wallHeight);
        if (d >= smallest) c.fail(`${path}.diameter_m`, `expected a balloon smaller than the room's smallest side (${smallest} m), found ${d} m`);
        if ("spawn" in g) {
          const spawn = g.spawn;
          if (!isObject(spawn)) {
            c.fail(`${path}.spawn`, `expected a table with min and max, found ${kind(spawn)}`);
          } else {
            c.unknownKeys(spawn, `${path}.spawn`, ["min", "max"]);
            const min = c.vector(spawn, "min", `${path}.spawn`, MAX_ROOM_SIZE_M, Infinity, "m");
            const max = c.vector(spawn, "max", `${path}.spawn`, MAX_ROOM_SIZE_M, Infinity, "m");
            if (!("min" in spawn) || !("max" in spawn)) c.fail(`${path}.spawn`, "expected both min and max");
            if (min && max) {
              const lo = [-width / 2, 0, -depth / 2];
              const hi = [width / 2, top, depth / 2];
              for (let a = 0; a < 3; a++) {
                if (max[a] < min[a]) c.fail(`${path}.spawn.max`, `expected max[${a}] ≥ min[${a}] (${min[a]}), found ${max[a]}`);
                else if (min[a] < lo[a] || max[a] > hi[a]) c.fail(`${path}.spawn`, `expected a region inside the room, from [${lo}] to [${hi}] m`);
                if (a !== 1 && max[a] - min[a] < d) c.fail(`${path}.spawn`, `expected a region at least one balloon (${d} m) wide along ${"xyz"[a]}`);
              }
            }
          }
        }
      });
    }
  }
  return c.problems;
}
