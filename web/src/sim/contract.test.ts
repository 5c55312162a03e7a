// The page and the engine agree: the strides the page reads frames with, the
// colours it offers, the scene limits it uses, and the answer to "is this
// scene valid?" all come from the built module. Needs the wasm build.

import { beforeAll, describe, expect, it } from "vitest";
import { POSE_STRIDE } from "./poseLayout";
import { decodeSceneParam, toBase64Url } from "../scene/sceneLink";
import { applyParams, paramsFromScene } from "../scene/sceneParams";
import { engineConstants, setEngineConstants } from "../scene/sceneSchema";
import { loadBuiltEngine } from "./builtEngine";
import { Engine, EngineError, type LiveSetting, type Scene } from "./engine";
import { LIVE_LINES } from "../ui/panel";
import { CONTACT_STRIDE, RIBBON_POINT_STRIDE, SQUASH_STRIDE, checkLayout, frameFloats } from "./frameLayout";

let engine: Engine;

beforeAll(async () => {
  engine = await loadBuiltEngine();
  setEngineConstants(engine.constants, engine.defaultSceneJson());
});

const b64 = (text: string) => toBase64Url(new TextEncoder().encode(text));

/** What the page says of `scene` when a link or the panel brings it: null when accepted. */
function pageVerdict(scene: unknown): string | null {
  return engine.validateScene(JSON.stringify(scene));
}

describe("strides", () => {
  it("the page reads frames with the module's strides", () => {
    expect(engine.constants.pose_stride).toBe(POSE_STRIDE);
    expect(engine.constants.contact_stride).toBe(CONTACT_STRIDE);
    expect(() => checkLayout(engine.constants)).not.toThrow();
    expect(engine.constants.ribbon_point_stride).toBe(RIBBON_POINT_STRIDE);
    expect(() => checkLayout(engine.constants)).not.toThrow();
    const page = { pose_stride: POSE_STRIDE, contact_stride: CONTACT_STRIDE, ribbon_point_stride: RIBBON_POINT_STRIDE };
    expect(() => checkLayout({ ...page, pose_stride: POSE_STRIDE + 1 })).toThrow(/floats per pose/);
    expect(() => checkLayout({ ...page, ribbon_point_stride: RIBBON_POINT_STRIDE + 1 })).toThrow(/floats per ribbon point/);
  });

  it("poses and contacts come as views of exactly those strides", () => {
    engine.loadDefaultScene();
    engine.step(30);
    const n = engine.bodyCount();
    const poses = engine.poses();
    expect(poses.length).toBe(n * POSE_STRIDE);
    for (let i = 0; i < n; i++) {
      const q = poses.subarray(i * POSE_STRIDE + 3, i * POSE_STRIDE + 7);
      expect(Math.hypot(...q)).toBeCloseTo(1, 3);
    }
    const contacts = engine.contacts(1_000_000);
    expect(contacts.view.length).toBe(contacts.count * CONTACT_STRIDE);
    expect(frameFloats(n, contacts.count)).toBe(2 * poses.length + contacts.view.length + n + n * SQUASH_STRIDE);
  });
});

/** The panel's ribbon length line, as the engine takes it. */
const ribbonLength = (value: number) => engine.applyLive({ control: "ribbon_length", value });

describe("ribbons", () => {
  /** Ribbon r's points as [x, y, z] triples. */
  const pointsOf = (r: number) => {
    const { offsets } = engine.ribbons();
    const all = engine.ribbonPoints();
    const out: number[][] = [];
    for (let i = offsets[r]; i < offsets[r + 1]; i++) out.push(Array.from(all.subarray(i * RIBBON_POINT_STRIDE, (i + 1) * RIBBON_POINT_STRIDE)));
    return out;
  };

  it("come in one array of points, with each ribbon's first point, balloon and colour", () => {
    engine.loadDefaultScene();
    ribbonLength(1.5);
    const n = engine.bodyCount();
    expect(engine.ribbonLength()).toBe(1.5);
    expect(engine.ribbonCount()).toBe(n);
    const tables = engine.ribbons();
    expect(tables.offsets.length).toBe(n + 1);
    expect(tables.offsets[0]).toBe(0);
    expect(tables.offsets[n]).toBe(engine.ribbonPointCount());
    const points = engine.ribbonPoints();
    expect(points.length).toBe(engine.ribbonPointCount() * RIBBON_POINT_STRIDE);
    expect(frameFloats(n, 0, points.length)).toBe(2 * n * POSE_STRIDE + 2 * points.length + n + n * SQUASH_STRIDE);
    expect([...tables.bodies].sort((a, b) => a - b)).toEqual([...Array(n).keys()]);
    for (const c of tables.colors) expect(c).toBeLessThanOrEqual(0xffffff);
    expect(Array.from(tables.weights), "the default ribbons carry no weight").toEqual(Array(n).fill(0));
    const poses = engine.poses().slice();
    for (let r = 0; r < n; r++) {
      const ribbon = pointsOf(r);
      const b = tables.bodies[r] * POSE_STRIDE;
      const knot = ribbon[0];
      expect(knot[1], "the knot hangs below its balloon's centre").toBeLessThan(poses[b + 1]);
      expect(Math.hypot(knot[0] - poses[b], knot[1] - poses[b + 1], knot[2] - poses[b + 2])).toBeLessThan(0.4);
      let along = 0;
      for (let i = 1; i < ribbon.length; i++) along += Math.hypot(...ribbon[i].map((v, k) => v - ribbon[i - 1][k]));
      expect(along).toBeCloseTo(1.5, 2);
    }
    engine.step(10);
    expect(engine.stats().ribbons).toBe(n);
    const stretch = engine.stats().ribbon_max_stretch;
    expect(Number.isFinite(stretch) && stretch >= 0).toBe(true);
  });

  it("are tied to balloons added later, and untied by a length of 0", () => {
    engine.loadDefaultScene();
    ribbonLength(0.8);
    const n = engine.bodyCount();
    engine.addBalloonOnFloor(0.5, 0.5, 0);
    expect(engine.ribbonCount()).toBe(n + 1);
    engine.remove(0);
    expect(engine.ribbonCount(), "a popped balloon takes its ribbon").toBe(n);
    ribbonLength(0);
    expect(engine.ribbonCount()).toBe(0);
    expect(engine.ribbonPoints().length).toBe(0);
    engine.addBalloonOnFloor(-0.5, 0.5, 0);
    expect(engine.ribbonCount()).toBe(0);
  });

  it("a ribbon's free end pulled down brings its balloon down", () => {
    engine.loadDefaultScene();
    engine.step(600); // to the ceiling
    ribbonLength(1);
    engine.step(30);
    const { bodies } = engine.ribbons();
    const ribbon = pointsOf(0);
    const end = ribbon.length - 1;
    const tip = ribbon[end];
    const heightOf = () => engine.poses()[bodies[0] * POSE_STRIDE + 1];
    const before = heightOf();
    engine.grabRibbon(0, end, tip[0], tip[1], tip[2]);
    engine.dragTo(tip[0], 0.3, tip[2]);
    engine.step(120);
    expect(heightOf()).toBeLessThan(before - 1);
    engine.release();
  });

  it("refuses a bad length or grab, naming it, and keeps the world", () => {
    engine.loadDefaultScene();
    ribbonLength(1);
    const hash = engine.stateHash();
    const ribbons = engine.ribbonCount();
    const calls: [() => void, string][] = [
      [() => ribbonLength(engine.constants.max_ribbon_length_m + 1), "OutOfRange"],
      [() => ribbonLength(-1), "OutOfRange"],
      [() => ribbonLength(NaN), "BadArgument"],
      [() => engine.grabRibbon(ribbons, 1, 0, 1, 0), "OutOfRange"],
      [() => engine.grabRibbon(0, 0, 0, 1, 0), "OutOfRange"],
      [() => engine.grabRibbon(0, 1, 0, NaN, 0), "BadArgument"],
    ];
    for (const [call, kind] of calls) {
      let thrown: unknown = null;
      try {
        call();
      } catch (e) {
        thrown = e;
      }
      expect(thrown).toBeInstanceOf(EngineError);
      expect((thrown as EngineError).kind).toBe(kind);
      expect((thrown as EngineError).message).toMatch(/^(apply_live|grab_ribbon): /);
    }
    expect(engine.stateHash()).toBe(hash);
    expect(engine.ribbonLength()).toBe(1);
  });
});

describe("live settings", () => {
  it("the page's LiveSetting type and the engine's enum name the same controls, each with a range", () => {
    // Exhaustive over the generated union: a control added in Rust fails to compile here until named.
    const named: Record<LiveSetting["control"], true> = { ribbon_length: true, gravity: true };
    const ranges = engine.constants.live;
    expect(ranges.map((r) => r.control).sort()).toEqual(Object.keys(named).sort());
    for (const r of ranges) expect(r.min).toBeLessThan(r.max);
    expect(ranges.find((r) => r.control === "ribbon_length")?.max).toBe(engine.constants.max_ribbon_length_m);
    // Every live control has its panel line.
    expect(LIVE_LINES.map((l) => l.control).sort()).toEqual(Object.keys(named).sort());
  });

  it("gravity is taken by the running world: a moon room's net lift is a sixth of Earth's, and the scene says so", () => {
    engine.loadDefaultScene();
    engine.step(1);
    const earth = engine.bodyCard(0);
    const before = engine.bodyCount();
    engine.applyLive({ control: "gravity", value: 1.62 });
    expect(engine.bodyCount(), "the world is not rebuilt").toBe(before);
    const moon = engine.bodyCard(0);
    expect(moon.net_lift_n / earth.net_lift_n).toBeCloseTo(1.62 / 9.81, 3);
    expect(moon.net_lift_g).toBeCloseTo(earth.net_lift_g, 3);
    const scene = JSON.parse(engine.sceneJson()) as Scene;
    expect(scene.sim?.gravity).toEqual([0, -1.62, 0]);
    for (const [value, kind] of [[-1, "OutOfRange"], [NaN, "BadArgument"]] as const) {
      expect(() => engine.applyLive({ control: "gravity", value })).toThrow(EngineError);
      try {
        engine.applyLive({ control: "gravity", value });
      } catch (e) {
        expect((e as EngineError).kind).toBe(kind);
      }
    }
    // Not a control of the engine: refused as a bad argument, and the engine goes on.
    let unknown: unknown = null;
    try {
      engine.applyLive({ control: "wind", value: 1 } as unknown as LiveSetting);
    } catch (e) {
      unknown = e;
    }
    expect((unknown as EngineError).kind).toBe("BadArgument");
    expect((unknown as EngineError).message).toMatch(/^apply_live: /);
    engine.step(1);
  });
});

describe("gas and time-lapse", () => {
  it("every frame's scales are one per body, 1 at the fill, below 1 after an hour", () => {
    engine.loadDefaultScene();
    const n = engine.bodyCount();
    let scales = engine.bodyScales();
    expect(scales.length).toBe(n);
    const squash = engine.bodySquash();
    expect(squash.length).toBe(n * SQUASH_STRIDE);
    expect(frameFloats(n, 0, 0)).toBe(2 * n * POSE_STRIDE + scales.length + squash.length);
    for (const s of scales) expect(s).toBeCloseTo(1, 1);
    expect(engine.simTime()).toBe(0);
    expect(engine.airTemperatureC()).toBeCloseTo(20, 3);
    let steps = 0;
    let jumps = 0;
    while (engine.simTime() < 3600) {
      const done = engine.advance(Math.min(60, 3600 - engine.simTime()), 200);
      expect(done.seconds).toBeGreaterThan(0);
      steps += done.steps;
      jumps += done.jumps;
    }
    expect(engine.simTime()).toBeCloseTo(3600, 3);
    expect(jumps, `the sleeping pile jumps (${steps} steps)`).toBeGreaterThan(0);
    scales = engine.bodyScales();
    for (const s of scales) expect(s).toBeLessThan(1);
    const counts = engine.floatCounts();
    expect(counts.ceiling + counts.hovering + counts.floor).toBe(n);
    expect(counts.groups.length).toBe(1);
    expect(counts.time_s).toBeCloseTo(engine.simTime(), 6);
    expect(counts.mean_lift_fraction).toBeGreaterThan(0);
    expect(counts.mean_lift_fraction).toBeLessThan(1);
  }, 120_000);

  it("a balloon added by the page carries its group's gas", () => {
    engine.loadDefaultScene();
    const n = engine.bodyCount();
    engine.addBalloonOnFloor(0.5, 0.5, 0);
    while (engine.simTime() < 1200) engine.advance(60, 1000);
    expect(engine.bodyScales()[n]).toBeLessThan(1);
  }, 120_000);

  it("refuses a bad span or budget, naming advance, and keeps the world", () => {
    engine.loadDefaultScene();
    const hash = engine.stateHash();
    for (const [seconds, steps] of [
      [NaN, 10],
      [-1, 10],
      [engine.constants.max_advance_s + 1, 10],
      [1, 0],
      [1, engine.constants.max_steps_per_call + 1],
    ]) {
      let thrown: unknown = null;
      try {
        engine.advance(seconds, steps);
      } catch (e) {
        thrown = e;
      }
      expect(thrown).toBeInstanceOf(EngineError);
      expect((thrown as EngineError).kind).toBe("BadArgument");
      expect((thrown as EngineError).message).toMatch(/^advance: /);
    }
    expect(engine.stateHash()).toBe(hash);
    expect(engine.simTime()).toBe(0);
  });
});

describe("foil models", () => {
  it("the engine says which models are foil and hands over their surface in the page's stride", () => {
    engine.loadSceneJson(
      JSON.stringify({ balloons: [{ count: 2 }, { count: 3, kind: "foil", size_in: 18 }] }),
    );
    expect(engine.worldInfo().foil).toEqual([false, true]);
    const stride = engine.constants.mesh_vertex_stride;
    expect(stride).toBe(3);
    const mesh = engine.modelMesh(1);
    const vertices = mesh.positions.length / stride;
    expect(Number.isInteger(vertices) && vertices > 100).toBe(true);
    expect(mesh.normals.length).toBe(mesh.positions.length);
    expect(mesh.indices.length % 3).toBe(0);
    expect(Math.max(...mesh.indices)).toBe(vertices - 1);
    // An 18-inch pillow standing on edge: about 46 cm across in x, 12.5 cm thick in z.
    const extent = (axis: number) => {
      const c = mesh.positions.filter((_, i) => i % stride === axis);
      return Math.max(...c) - Math.min(...c);
    };
    expect(extent(0)).toBeCloseTo(18 * engine.constants.scene.metres_per_inch, 2);
    expect(extent(2)).toBeGreaterThan(0.1);
    expect(extent(2)).toBeLessThan(0.15);
    // Copies: a later call does not change them.
    const first = mesh.positions[0];
    engine.modelMesh(0);
    expect(mesh.positions[0]).toBe(first);
    expect(() => engine.modelMesh(2)).toThrow(/write_model_mesh: balloon model 2/);
    engine.loadDefaultScene();
    expect(engine.worldInfo().foil.every((f) => !f)).toBe(true);
  });
});

describe("colours", () => {
  it("every colour the engine names is accepted by it, and drawn in the RGB it lists", () => {
    const names = engine.constants.colors.map((c) => c.name);
    expect(names.length).toBeGreaterThanOrEqual(6);
    const scene = { balloons: [{ count: names.length, colors: names }] };
    expect(pageVerdict(scene)).toBeNull();
    engine.loadSceneJson(JSON.stringify(scene));
    const info = engine.worldInfo();
    expect(info.color_names).toEqual(names);
    for (let i = 0; i < names.length; i++) {
      for (let c = 0; c < 3; c++) expect(info.colors[i][c]).toBeCloseTo(engine.constants.colors[i].rgb[c], 6);
    }
  });

  it("a colour the engine does not know is refused by the page with the engine's message", () => {
    const message = pageVerdict({ balloons: [{ colors: ["red", "gold"] }] });
    expect(message).toMatch(/balloons\[0\]\.colors\[1\]/);
    expect(message).toMatch(/gold/);
    // A shared link carries it to the engine, which refuses it in the same words.
    const link = decodeSceneParam(b64(JSON.stringify({ balloons: [{ colors: ["red", "gold"] }] })));
    expect(link.ok).toBe(true);
    if (!link.ok) return;
    let thrown: unknown = null;
    try {
      engine.loadSceneJson(link.json);
    } catch (e) {
      thrown = e;
    }
    expect(thrown).toBeInstanceOf(EngineError);
    expect((thrown as EngineError).kind).toBe("Scene");
    expect((thrown as EngineError).message).toBe(message);
  });
});

describe("scene validation is the engine's", () => {
  it("accepts the empty scene, the default scene, and what the panel writes", () => {
    expect(pageVerdict({})).toBeNull();
    expect(engine.validateScene(engine.defaultSceneJson())).toBeNull();
    const base = JSON.parse(engine.defaultSceneJson()) as Scene;
    const p = { ...paramsFromScene(base), count: 7, sizeIn: 16, helium: false, ceiling: "flat" as const, friction: 0.2 };
    expect(pageVerdict(applyParams(base, p))).toBeNull();
  });

  it("refuses, naming the key, what the engine refuses", () => {
    const limits = engineConstants().scene;
    const cases: [unknown, string][] = [
      [{ rooms: {} }, "rooms"],
      [{ sim: { substep: 4 } }, "substep"],
      [{ room: { width: "6" } }, "room.width"],
      [{ room: { width: limits.max_room_size_m * 2 } }, "room.width"],
      [{ room: { ceiling: "dome" } }, "dome"],
      [{ sim: { substeps: 0 } }, "sim.substeps"],
      [{ sim: { restitution: 1.5 } }, "sim.restitution"],
      [{ sim: { friction: 11 } }, "sim.friction"],
      [{ air: { pressure_kpa: 10 } }, "air.pressure_kpa"],
      [{ balloons: [{ gas: "hydrogen" }] }, "hydrogen"],
      [{ balloons: [{ diameter_m: limits.max_balloon_diameter_m + 1 }] }, "balloons[0].diameter_m"],
      [{ balloons: [{ leaves: limits.max_leaves + 1 }] }, "balloons[0].leaves"],
      [{ balloons: Array.from({ length: limits.max_balloon_groups + 1 }, () => ({ count: 0 })) }, "balloons"],
      [{ room: { mesh: "room.obj" } }, "room.mesh"],
    ];
    for (const [scene, key] of cases) {
      const message = pageVerdict(scene);
      expect(message, JSON.stringify(scene)).not.toBeNull();
      expect(message, JSON.stringify(scene)).toContain(key);
    }
  });

  it("refuses more balloons than the page holds, with the engine's capacity", () => {
    const { capacity } = engine.constants;
    const message = pageVerdict({ room: { width: 100, depth: 100 }, balloons: [{ count: capacity + 1 }] });
    expect(message).toContain(String(capacity));
  });
});

describe("errors", () => {
  it("a refused call throws an EngineError of one of the module's kinds, and the world stays", () => {
    engine.loadDefaultScene();
    const n = engine.bodyCount();
    const hash = engine.stateHash();
    const kinds = new Set(engine.constants.error_kinds);
    const calls: [() => void, string][] = [
      [() => engine.addBalloon(NaN, 1, 0, 0), "BadArgument"],
      [() => engine.remove(n), "OutOfRange"],
      [() => engine.remove(-1), "OutOfRange"],
      [() => engine.step(engine.constants.max_steps_per_call + 1), "BadArgument"],
      [() => engine.modelTree(99), "OutOfRange"],
      [() => engine.setVelocity(0, [engine.constants.max_speed * 2, 0, 0], [0, 0, 0]), "BadArgument"],
    ];
    for (const [call, kind] of calls) {
      let thrown: unknown = null;
      try {
        call();
      } catch (e) {
        thrown = e;
      }
      expect(thrown).toBeInstanceOf(EngineError);
      expect((thrown as EngineError).kind).toBe(kind);
      expect(kinds.has(kind)).toBe(true);
    }
    expect(engine.bodyCount()).toBe(n);
    expect(engine.stateHash()).toBe(hash);
    engine.step(1);
  });
});
