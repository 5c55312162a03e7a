import { describe, expect, it } from "vitest";
import { decodeSceneParam, encodeSceneHash, fromBase64Url, sceneParam, toBase64Url } from "./sceneLink";

const scene = {
  room: { width: 6, depth: 6, wall_height: 3, ceiling: "pyramid", apex_height: 1.5 },
  balloons: [{ count: 50, colors: ["red", "yellow", "#10a0ff"], size_in: 11 }],
  air: { temperature_c: 20, pressure_kpa: 101.325 },
  sim: { seed: 7, substeps: 4, friction: 0.5, restitution: 0.4, gravity: [0, -9.81, 0], sleep: true },
};

const b64 = (text: string) => toBase64Url(new TextEncoder().encode(text));

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

  it("leaves the scene's validity to the engine: a valid link with an unknown colour decodes", () => {
    // The engine refuses it when the worker loads it (sim/contract.test.ts).
    const decoded = decodeSceneParam(b64(JSON.stringify({ balloons: [{ colors: ["gold"] }] })));
    expect(decoded.ok).toBe(true);
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
    expect(error(b64("[1, 2]"))).toMatch(/not a JSON object/);
    expect(error(b64("null"))).toMatch(/not a JSON object/);
    expect(error("a".repeat(300_000))).toMatch(/at most/);
  });
});
