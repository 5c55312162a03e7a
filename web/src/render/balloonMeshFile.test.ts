import { readFileSync } from "node:fs";
import { fileURLToPath } from "node:url";
import { describe, expect, it } from "vitest";
import { bakeBalloonMeshFile } from "../../scripts/balloonMeshPlugin";
import { BALLOON_MESH_FILE, decodeBalloonMesh, encodeBalloonMesh } from "./balloonMeshFile";
import { balloonAssetsOf } from "./balloons";

const assets = fileURLToPath(new URL("../../../assets", import.meta.url));
const objLines = readFileSync(`${assets}/balloon.obj`, "utf8").split("\n");
/** The OBJ's own vertices, and its faces' corners as indices into them. */
const objVertices = objLines.filter((l) => l.startsWith("v ")).map((l) => l.split(/\s+/).slice(1, 4).map(Number));
const objFaces = objLines.filter((l) => l.startsWith("f ")).map((l) => l.split(/\s+/).slice(1).map((c) => Number(c.split("/")[0]) - 1));

const bytes = bakeBalloonMeshFile(assets);
const copy = (b: Uint8Array) => b.slice().buffer;

describe("the baked balloon mesh", () => {
  const mesh = decodeBalloonMesh(copy(bytes));
  const vertices = mesh.positions.length / 3;
  const at = (i: number) => [mesh.positions[3 * i], mesh.positions[3 * i + 1], mesh.positions[3 * i + 2]];

  it("is the OBJ welded: every face a triangle of its vertices, no vertex twice", () => {
    expect(objFaces.every((f) => f.length === 3)).toBe(true);
    expect(mesh.index.length).toBe(3 * objFaces.length);
    const keys = new Set<string>();
    for (let i = 0; i < vertices; i++) keys.add(at(i).map((c) => c.toFixed(5)).join(","));
    expect(keys.size).toBe(vertices);
    expect(vertices).toBeLessThanOrEqual(objVertices.length);
    // Each triangle of the file sits on the OBJ's face of the same order.
    for (const t of [0, 17, 1000, objFaces.length - 1]) {
      for (let c = 0; c < 3; c++) {
        const got = at(mesh.index[3 * t + c]);
        const want = objVertices[objFaces[t][c]];
        for (let k = 0; k < 3; k++) expect(got[k]).toBeCloseTo(want[k], 5);
      }
    }
  });

  it("has smooth unit normals pointing out of the balloon", () => {
    let outward = 0;
    for (let i = 0; i < vertices; i++) {
      const [x, y, z] = [mesh.normals[3 * i], mesh.normals[3 * i + 1], mesh.normals[3 * i + 2]];
      expect(Math.hypot(x, y, z)).toBeCloseTo(1, 5);
      const [px, , pz] = at(i);
      if (px * x + pz * z >= 0) outward++;
    }
    expect(outward).toBe(vertices);
  });

  it("carries each MTL file's colour by its name", () => {
    const red = readFileSync(`${assets}/balloon_red.mtl`, "utf8").match(/^Kd (.+)$/m)![1].split(/\s+/).map(Number);
    expect(mesh.colors.red).toEqual(red);
    expect(Object.keys(mesh.colors).sort()).toEqual(["blue", "green", "orange", "pink", "purple", "red", "white", "yellow"]);
  });

  it("comes out the same on every build and round-trips bit for bit", () => {
    expect(bakeBalloonMeshFile(assets)).toEqual(bytes);
    expect(encodeBalloonMesh(mesh)).toEqual(bytes);
  });

  it("gives the page the model's diameter and a crowd mesh of the same height", () => {
    const a = balloonAssetsOf(mesh);
    const xs = objVertices.map((v) => v[0]);
    expect(a.diameter).toBeCloseTo(Math.max(...xs) - Math.min(...xs), 4);
    a.crowdGeometry.computeBoundingBox();
    expect(a.crowdGeometry.boundingBox!.max.y).toBeCloseTo(a.geometry.boundingBox!.max.y, 4);
    expect(a.mtlColors.get("red")).toEqual(mesh.colors.red);
  });

  it("refuses a file that is not one, or is cut short", () => {
    expect(() => decodeBalloonMesh(new TextEncoder().encode("v 0 0 0\nf 1 2 3\n").buffer)).toThrow(BALLOON_MESH_FILE);
    expect(() => decodeBalloonMesh(copy(bytes.subarray(0, bytes.length - 4)))).toThrow(/length/);
  });
});
