// The furniture drawn from the engine's own triangles (those the balloons
// collide with, in the room's mesh): every piece in one mesh, flat shaded,
// in a varnished oak with its grain running along x, casting shadows on the
// floor and taking the balloons'.

import * as THREE from "three";
import type { FurnitureMesh } from "../sim/engine";
import { repeatingTexture } from "./room";

/** World positions, one triangle after another (flat: no shared vertices). */
export function furniturePositions(mesh: FurnitureMesh): Float32Array {
  const t = mesh.triangles;
  const v = mesh.vertices;
  const out = new Float32Array(t.length * 3);
  for (let k = 0; k < t.length; k++) {
    out[3 * k] = v[3 * t[k]];
    out[3 * k + 1] = v[3 * t[k] + 1];
    out[3 * k + 2] = v[3 * t[k] + 2];
  }
  return out;
}

/**
 * Box-mapped texture coordinates, 1 per 0.5 m: each face takes the two axes
 * across its normal, the grain running along x (z on faces that look along x).
 */
export function furnitureUvs(positions: Float32Array): Float32Array {
  const uv = new Float32Array((positions.length / 3) * 2);
  const a = new THREE.Vector3();
  const b = new THREE.Vector3();
  const c = new THREE.Vector3();
  for (let f = 0; f < positions.length; f += 9) {
    a.fromArray(positions, f);
    b.fromArray(positions, f + 3);
    c.fromArray(positions, f + 6);
    const n = b.clone().sub(a).cross(c.clone().sub(a));
    const [ax, ay, az] = [Math.abs(n.x), Math.abs(n.y), Math.abs(n.z)];
    for (let k = 0; k < 3; k++) {
      const p = f + 3 * k;
      const [x, y, z] = [positions[p], positions[p + 1], positions[p + 2]];
      // Grain along the longer horizontal run: x on tops and z-facing sides, z on x-facing sides.
      const [u, w] = ay >= ax && ay >= az ? [x, z] : ax >= az ? [z, y] : [x, y];
      const o = (p / 3) * 2;
      uv[o] = u * 2;
      uv[o + 1] = w * 2;
    }
  }
  return uv;
}

function woodTexture(): THREE.CanvasTexture {
  // Oak: warm streaks along u, a few darker growth lines, drawn once.
  const canvas = document.createElement("canvas");
  canvas.width = 256;
  canvas.height = 256;
  const g = canvas.getContext("2d")!;
  g.fillStyle = "rgb(150, 98, 56)";
  g.fillRect(0, 0, 256, 256);
  let seed = 11;
  const rand = () => ((seed = (seed * 16807) % 2147483647) / 2147483647);
  for (let i = 0; i < 90; i++) {
    const y = rand() * 256;
    const dark = rand() < 0.3;
    g.strokeStyle = dark ? `rgba(70, 40, 18, ${0.25 + rand() * 0.25})` : `rgba(190, 135, 80, ${0.15 + rand() * 0.2})`;
    g.lineWidth = dark ? 1 + rand() * 1.5 : 2 + rand() * 4;
    g.beginPath();
    g.moveTo(0, y);
    g.bezierCurveTo(85, y + rand() * 8 - 4, 170, y + rand() * 8 - 4, 256, y);
    g.stroke();
  }
  return repeatingTexture(canvas);
}

/** The furniture as one mesh, or null when the room has none. */
export function buildFurniture(mesh: FurnitureMesh): THREE.Mesh | null {
  if (mesh.triangles.length === 0) return null;
  const positions = furniturePositions(mesh);
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute("position", new THREE.Float32BufferAttribute(positions, 3));
  geometry.setAttribute("uv", new THREE.Float32BufferAttribute(furnitureUvs(positions), 2));
  // Unshared vertices: each face keeps its own normal (crisp edges).
  geometry.computeVertexNormals();
  const material = new THREE.MeshStandardMaterial({ map: woodTexture(), roughness: 0.5, metalness: 0 });
  const out = new THREE.Mesh(geometry, material);
  out.name = "furniture";
  out.castShadow = true;
  out.receiveShadow = true;
  return out;
}
