import { describe, expect, it } from "vitest";
import { colorNameOfMtlFile, parseMtl } from "./mtl";

describe("MTL", () => {
  it("reads Kd, Ks and Ns of each material", () => {
    const m = parseMtl("# red latex\nnewmtl latex_red\nNs 250.0\nKd 0.8 0.05 0.04\nKs 0.5 0.5 0.5\n\nnewmtl other\nKd 1 1 1 # white\n");
    expect(m).toEqual([
      { name: "latex_red", kd: [0.8, 0.05, 0.04], ks: [0.5, 0.5, 0.5], ns: 250 },
      { name: "other", kd: [1, 1, 1], ks: null, ns: null },
    ]);
  });

  it("ignores malformed lines", () => {
    expect(parseMtl("Kd 1 1 1\nnewmtl a\nKd x y z\n")).toEqual([{ name: "a", kd: null, ks: null, ns: null }]);
  });

  it("finds the colour in a file name", () => {
    expect(colorNameOfMtlFile("assets/balloon_red.mtl")).toBe("red");
    expect(colorNameOfMtlFile("balloon-Blue.mtl")).toBe("blue");
    expect(colorNameOfMtlFile("balloon.obj")).toBeNull();
  });
});
