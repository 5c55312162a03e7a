import { describe, expect, it } from "vitest";
import * as THREE from "three";
import { outlineMatrix } from "./selectionOutline";

describe("the selection outline's shell", () => {
  it("is the balloon grown about its centre: the centre stays, a point on the surface moves out", () => {
    const scale = 0.8;
    const drawn = new THREE.Matrix4().compose(new THREE.Vector3(1, 2, 3), new THREE.Quaternion().setFromEuler(new THREE.Euler(0.3, 0.5, 0.1)), new THREE.Vector3(scale, scale, scale));
    // The root sphere's centre in the body frame at the drawn size, and in the mesh's units.
    const center = new THREE.Vector3(0, 0.12, 0).multiplyScalar(scale);
    const meshCenter = center.clone().divideScalar(scale);
    const m = outlineMatrix(new THREE.Matrix4(), drawn, center, scale, 1.1);
    const c1 = meshCenter.clone().applyMatrix4(drawn);
    const c2 = meshCenter.clone().applyMatrix4(m);
    expect(c2.distanceTo(c1)).toBeLessThan(1e-6);
    // A point 0.14 m (mesh units) from the centre ends 1.1 times as far from it.
    const p = meshCenter.clone().add(new THREE.Vector3(0.14, 0, 0));
    const d1 = p.clone().applyMatrix4(drawn).distanceTo(c1);
    const d2 = p.clone().applyMatrix4(m).distanceTo(c1);
    expect(d2 / d1).toBeCloseTo(1.1, 6);
  });
});
