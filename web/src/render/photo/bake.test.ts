import { describe, expect, it } from "vitest";
import * as THREE from "three";
import { bakeInstances, bakeRibbons, bakeScene, rgba } from "./bake";
import { STRIP_VERTICES } from "./ribbonStrip";
import { CURL_LENGTH, CURL_RADIUS } from "../ribbons";

// One triangle in the xy plane, facing +z.
const TRI_POS = [0, 0, 0, 1, 0, 0, 0, 1, 0];
const TRI_NRM = [0, 0, 1, 0, 0, 1, 0, 0, 1];

function matrices(...ms: THREE.Matrix4[]): Float32Array {
  const out = new Float32Array(ms.length * 16);
  ms.forEach((m, i) => m.toArray(out, i * 16));
  return out;
}

describe("bakeInstances", () => {
  it("moves each instance's vertices by its matrix, as three's InstancedMesh draws them", () => {
    const rotate = new THREE.Quaternion().setFromAxisAngle(new THREE.Vector3(0, 1, 0), 0.7);
    const a = new THREE.Matrix4().compose(new THREE.Vector3(1, 2, 3), rotate, new THREE.Vector3(2, 2, 2));
    const b = new THREE.Matrix4().makeTranslation(-5, 0, 0.5);
    const out = bakeInstances(TRI_POS, TRI_NRM, [0, 1, 2], matrices(a, b), 2, [1, 0, 0, 0, 0.5, 1]);
    expect(out.positions.length).toBe(18);
    for (const [k, m] of [a, b].entries()) {
      for (let v = 0; v < 3; v++) {
        const expected = new THREE.Vector3().fromArray(TRI_POS, v * 3).applyMatrix4(m);
        const got = new THREE.Vector3().fromArray(out.positions, (k * 3 + v) * 3);
        expect(got.distanceTo(expected)).toBeLessThan(1e-5);
        const n = new THREE.Vector3().fromArray(TRI_NRM, v * 3).applyNormalMatrix(new THREE.Matrix3().getNormalMatrix(m));
        expect(new THREE.Vector3().fromArray(out.normals, (k * 3 + v) * 3).distanceTo(n)).toBeLessThan(1e-5);
      }
    }
    // Each vertex carries its instance's colour; the indices point at its own copy.
    expect(Array.from(out.colors!.slice(0, 3))).toEqual([1, 0, 0]);
    expect(Array.from(out.colors!.slice(9, 12))).toEqual([0, 0.5, 1]);
    expect(Array.from(out.indices)).toEqual([0, 1, 2, 3, 4, 5]);
  });

  it("keeps normals perpendicular to a stretched instance's surface (inverse transpose)", () => {
    // A slanted triangle, stretched 4× along x.
    const pos = [0, 0, 0, 1, 1, 0, 0, 0, 1];
    const n = new THREE.Vector3(1, -1, 0).normalize();
    const out = bakeInstances(pos, [n.x, n.y, n.z, n.x, n.y, n.z, n.x, n.y, n.z], null, matrices(new THREE.Matrix4().makeScale(4, 1, 1)), 1, null);
    const p = (i: number) => new THREE.Vector3().fromArray(out.positions, i * 3);
    const edge1 = p(1).sub(p(0));
    const edge2 = p(2).sub(p(0));
    const normal = new THREE.Vector3().fromArray(out.normals, 0);
    expect(Math.abs(normal.dot(edge1))).toBeLessThan(1e-6);
    expect(Math.abs(normal.dot(edge2))).toBeLessThan(1e-6);
    expect(normal.length()).toBeCloseTo(1, 6);
    // Same side as the input normal (the face still points the same way).
    expect(normal.x).toBeGreaterThan(0);
    expect(out.colors).toBeNull();
  });

  it("flips normals of a mirrored instance so they still point outward, and leaves out zero-scale instances", () => {
    const mirror = new THREE.Matrix4().makeScale(-1, 1, 1);
    const empty = new THREE.Matrix4().makeScale(0, 0, 0);
    const out = bakeInstances([1, 0, 0, 0, 1, 0, 0, 0, 1], [1, 0, 0, 0, 1, 0, 0, 0, 1], null, matrices(empty, mirror), 2, [9, 9, 9, 1, 1, 1]);
    expect(out.positions.length).toBe(9);
    expect(Array.from(out.normals.slice(0, 3))).toEqual([-1, 0, 0]);
    expect(Array.from(out.colors!.slice(0, 3))).toEqual([1, 1, 1]);
  });
});

describe("bakeRibbons", () => {
  /** A vertical ribbon of `n` points hanging from (x, top, 0), length `length`, as the live view's tables hold it. */
  function hanging(n: number, length: number, halfWidth: number) {
    const texels = new Float32Array(n * 4);
    for (let i = 0; i < n; i++) texels.set([0.5, 3 - (length * i) / (n - 1), -1, 0], i * 4);
    const geometry = new THREE.InstancedBufferGeometry();
    geometry.setAttribute("ribbon", new THREE.InstancedBufferAttribute(new Float32Array([0, n, length, 0.3]), 4));
    geometry.setAttribute("color", new THREE.InstancedBufferAttribute(new Float32Array([0.2, 0.4, 0.6]), 3));
    geometry.instanceCount = 1;
    return bakeRibbons({ mesh: new THREE.Mesh(geometry), texels, halfWidth });
  }

  it("draws a straight hanging ribbon as a strip of its width along its line, then a curl of the curl's radius", () => {
    const halfWidth = 0.0025;
    const length = 1.2;
    const out = hanging(9, length, halfWidth);
    expect(out.ribbons).toBe(1);
    expect(out.positions.length).toBe(STRIP_VERTICES * 3);
    const at = (v: number) => new THREE.Vector3().fromArray(out.positions, v * 3);
    // First sample: on the knot, across the strip by its full width.
    const a = at(0);
    const b = at(1);
    expect(a.distanceTo(b)).toBeCloseTo(2 * halfWidth, 6);
    expect(a.clone().add(b).multiplyScalar(0.5).distanceTo(new THREE.Vector3(0.5, 3, -1))).toBeLessThan(1e-6);
    // Every straight sample's centre lies on the vertical line; the curl's within its radius of it.
    const straightEnd = 3 - (length - CURL_LENGTH);
    for (let v = 0; v < STRIP_VERTICES; v += 2) {
      const mid = at(v).add(at(v + 1)).multiplyScalar(0.5);
      const off = Math.hypot(mid.x - 0.5, mid.z + 1);
      if (mid.y > straightEnd + 1e-6) expect(off).toBeLessThan(1e-6);
      else expect(off).toBeLessThan(CURL_RADIUS + 1e-6);
      expect(mid.y).toBeGreaterThan(3 - length - 1e-6);
      expect(mid.y).toBeLessThan(3 + 1e-6);
    }
    // Normals are unit, across the strip's width; the colour is the ribbon's.
    for (let v = 0; v < STRIP_VERTICES; v++) {
      const n = new THREE.Vector3().fromArray(out.normals, v * 3);
      expect(n.length()).toBeCloseTo(1, 5);
    }
    expect(Array.from(out.colors!.slice(-3))).toEqual([0.2, 0.4, 0.6].map((c) => Math.fround(c)));
    expect(Math.max(...out.indices)).toBe(STRIP_VERTICES - 1);
  });

  it("leaves out a ribbon whose points are not in the frame yet", () => {
    const geometry = new THREE.InstancedBufferGeometry();
    geometry.setAttribute("ribbon", new THREE.InstancedBufferAttribute(new Float32Array([4, 8, 1, 0]), 4));
    geometry.instanceCount = 1;
    const out = bakeRibbons({ mesh: new THREE.Mesh(geometry), texels: new Float32Array(8 * 4), halfWidth: 0.002 });
    expect(out.ribbons).toBe(0);
    expect(out.indices.length).toBe(0);
  });
});

describe("bakeScene", () => {
  it("gives every coloured mesh RGBA colours, as the tracer fills meshes without them (RGB would shift the merged array)", () => {
    const live = new THREE.Scene();
    const balloons = new THREE.InstancedMesh(new THREE.BoxGeometry(), new THREE.MeshPhysicalMaterial(), 2);
    balloons.setMatrixAt(0, new THREE.Matrix4().makeTranslation(1, 0, 0));
    balloons.setMatrixAt(1, new THREE.Matrix4().makeTranslation(-1, 0, 0));
    balloons.setColorAt(0, new THREE.Color(1, 0, 0));
    balloons.setColorAt(1, new THREE.Color(0, 0, 1));
    const floor = new THREE.Mesh(new THREE.PlaneGeometry(), new THREE.MeshStandardMaterial());
    const hidden = new THREE.Mesh(new THREE.PlaneGeometry(), new THREE.MeshStandardMaterial());
    hidden.visible = false;
    const debug = new THREE.Group();
    debug.add(new THREE.Mesh(new THREE.PlaneGeometry(), new THREE.MeshBasicMaterial()));
    live.add(balloons, floor, hidden, debug);
    const bake = bakeScene(live, [debug], null);
    expect(bake.scene.children.length, "the balloons and the floor; not the hidden mesh or the debug view").toBe(2);
    expect(bake.instances).toBe(2);
    const merged = bake.scene.children[0] as THREE.Mesh;
    const color = merged.geometry.getAttribute("color");
    expect(color.itemSize).toBe(4);
    expect([color.getX(0), color.getY(0), color.getZ(0), color.getW(0)]).toEqual([1, 0, 0, 1]);
    expect([color.getX(24), color.getY(24), color.getZ(24), color.getW(24)]).toEqual([0, 0, 1, 1]);
    expect((merged.material as THREE.Material).vertexColors).toBe(true);
    expect(Array.from(rgba([0.5, 0.25, 0], 3))).toEqual([0.5, 0.25, 0, 1]);
    bake.dispose();
  });
});
