import { describe, expect, it } from "vitest";
import { decodeSceneParam, encodeSceneHash, fromBase64Url, sceneParam, toBase64Url } from "./sceneLink";
import { validateScene } from "./sceneSchema";

const scene = {
  room: { width: 6, depth: 6, wall_height: 3, ceiling: "pyramid", apex_height: 1.5 },
  balloons: [{ count: 50, colors: ["red", "yellow", "#10a0ff"], size_in: 11 }],
  air: { temperature_c: 20, pressure_kpa: 101.325 },
  sim: { seed: 7, substeps: 4, friction: 0.5, restitution: 0.4, gravity: [0, -9.81, 0], sleep: true },
};

const b64 = (text: string) => toBase64Url(new TextEncoder().encode(text));
const keysOf = (s: unknown) => validateScene(s).map((p) => p.key);

describe("base64url", () => {
  it("round-trips arbitrary bytes without padding or URL-unsafe characters", () => {
    const bytes = new Uint8Array(300).map((_, i) => (i * 37) % 256);
    const text = toBase64Url(bytes);
    expect(text).toMatch(/^[A-Za-z0-9_-]*$/);
    expect(Array.from(fromBase64Url(text)!)).toEqual(Array.from(bytes));
  });

  it("rejects text that is not base64url", () => {
    expect(fromBase64Url("a+b/")).toBeNull();
    expect(fromBase64Url("abcde")).toBeNull();
    expect(fromBase64Url("%%%")).toBeNull();
  });
});

describe("scene link", () => {
  it("round-trips a scene through the hash", () => {
    const hash = encodeSceneHash(JSON.stringify(scene, null, 2));
    expect(hash.startsWith("#scene=")).toBe(true);
    const value = sceneParam(hash)!;
    const decoded = decodeSceneParam(value);
    expect(decoded.ok).toBe(true);
    if (decoded.ok) expect(decoded.scene).toEqual(scene);
  });

  it("accepts non-ASCII text (UTF-8)", () => {
    const decoded = decodeSceneParam(b64(JSON.stringify({ air: { temperature_c: 21.5 } }) + " "));
    expect(decoded.ok).toBe(true);
  });

  it("finds the scene parameter among others, and reports its absence", () => {
    expect(sceneParam("#a=1&scene=xyz&b=2")).toBe("xyz");
    expect(sceneParam("#a=1")).toBeNull();
    expect(sceneParam("")).toBeNull();
  });

  it("explains each kind of malformed link", () => {
    const error = (value: string) => {
      const r = decodeSceneParam(value);
      expect(r.ok).toBe(false);
      return r.ok ? "" : r.error;
    };
    expect(error("")).toMatch(/empty/);
    expect(error("not*base64")).toMatch(/not base64url/);
    expect(error("%%%garbage")).toMatch(/not base64url/);
    expect(error(toBase64Url(new Uint8Array([0xff, 0xfe, 0x00])))).toMatch(/not UTF-8/);
    expect(error(b64("{room: 1"))).toMatch(/not valid JSON/);
    expect(error(b64("[1, 2]"))).toMatch(/expected a JSON object/);
    expect(error(b64(JSON.stringify({ room: { width: -1 } })))).toMatch(/room\.width: expected a finite number in \[0\.5, 1000\] m, found -1/);
    expect(error("a".repeat(300_000))).toMatch(/at most/);
  });
});

describe("scene validation", () => {
  it("accepts the empty scene (all defaults) and a full one", () => {
    expect(validateScene({})).toEqual([]);
    expect(validateScene(scene)).toEqual([]);
  });

  it("rejects unknown keys, naming them", () => {
    expect(keysOf({ rooms: {} })).toEqual(["rooms"]);
    expect(keysOf({ sim: { substep: 4 } })).toEqual(["sim.substep"]);
    expect(keysOf({ balloons: [{ count: 1, colour: "red" }] })).toEqual(["balloons[0].colour"]);
  });

  it("rejects wrong types and out-of-range values", () => {
    expect(keysOf({ room: { width: "6" } })).toEqual(["room.width"]);
    expect(keysOf({ room: { ceiling: "dome" } })).toEqual(["room.ceiling"]);
    expect(keysOf({ sim: { substeps: 0 } })).toEqual(["sim.substeps"]);
    expect(keysOf({ sim: { substeps: 2.5 } })).toEqual(["sim.substeps"]);
    expect(keysOf({ sim: { restitution: 1.5 } })).toEqual(["sim.restitution"]);
    expect(keysOf({ sim: { dt: 0 } })).toEqual(["sim.dt"]);
    expect(keysOf({ sim: { sleep: "yes" } })).toEqual(["sim.sleep"]);
    expect(keysOf({ sim: { gravity: [0, -9.81] } })).toEqual(["sim.gravity"]);
    expect(keysOf({ air: { pressure_kpa: 10 } })).toEqual(["air.pressure_kpa"]);
    expect(keysOf({ balloons: {} })).toEqual(["balloons"]);
    expect(keysOf({ balloons: [{ count: -1 }] })).toEqual(["balloons[0].count"]);
    expect(keysOf({ balloons: [{ count: 300000 }] })).toContain("balloons[0].count");
    expect(keysOf({ balloons: [{ colors: ["red", "mauve-ish"] }] })).toEqual(["balloons[0].colors[1]"]);
    expect(keysOf({ balloons: [{ colors: [] }] })).toEqual(["balloons[0].colors"]);
    expect(keysOf({ balloons: [{ diameter_m: 0.3, size_in: 11 }] })).toEqual(["balloons[0].size_in"]);
    expect(keysOf({ balloons: [{ gas: "hydrogen" }] })).toEqual(["balloons[0].gas"]);
    expect(keysOf({ balloons: [{ velocity: [400, 0, 0] }] })).toEqual(["balloons[0].velocity"]);
    expect(keysOf({ balloons: [{ leaves: 40 }] })).toEqual(["balloons[0].leaves"]);
    expect(keysOf({ balloons: Array.from({ length: 65 }, () => ({ count: 0 })) })).toEqual(["balloons"]);
    expect(keysOf({ balloons: [{ colors: Array(65).fill("red") }] })).toEqual(["balloons[0].colors"]);
  });

  it("rejects a balloon larger than the room and a spawn box outside it", () => {
    expect(keysOf({ room: { wall_height: 1 }, balloons: [{ diameter_m: 2 }] })).toEqual(["balloons[0].diameter_m"]);
    expect(keysOf({ balloons: [{ spawn: { min: [-1, 0, -1], max: [1, 9, 1] } }] })).toEqual(["balloons[0].spawn"]);
    expect(keysOf({ balloons: [{ spawn: { min: [1, 0, -1], max: [-1, 1, 1] } }] })).toContain("balloons[0].spawn.max");
    expect(keysOf({ balloons: [{ spawn: { min: [-1, 0, -1], max: [1, 1, 1] } }] })).toEqual([]);
  });

  it("refuses a mesh room, which the browser cannot read", () => {
    expect(keysOf({ room: { mesh: "room.obj" } })).toEqual(["room.mesh"]);
  });
});
