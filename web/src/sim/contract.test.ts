// The page and the engine agree: the strides the page reads frames with, the
// colours it offers, the scene limits it uses, and the answer to "is this
// scene valid?" all come from the built module. Needs the wasm build.

import { beforeAll, describe, expect, it } from "vitest";
import { POSE_STRIDE } from "../render/poseMath";
import { decodeSceneParam, toBase64Url } from "../scene/sceneLink";
import { applyParams, paramsFromScene } from "../scene/sceneParams";
import { engineConstants, setEngineConstants } from "../scene/sceneSchema";
import { loadBuiltEngine } from "./builtEngine";
import { Engine, EngineError } from "./engine";
import { CONTACT_STRIDE, checkLayout, frameFloats } from "./frameLayout";

let engine: Engine;

beforeAll(async () => {
  engine = await loadBuiltEngine();
  setEngineConstants(engine.constants);
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
    expect(() => checkLayout({ pose_stride: POSE_STRIDE + 1, contact_stride: CONTACT_STRIDE })).toThrow(/floats per pose/);
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
    expect(frameFloats(n, contacts.count)).toBe(2 * poses.length + contacts.view.length);
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
    const base = JSON.parse(engine.defaultSceneJson()) as Record<string, unknown>;
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
