// The room drawn from the engine's own triangles (the mesh the balloons
// collide with): floor, walls and ceiling told apart by their normals, which
// point into the room. Faces are one-sided, so from outside the near walls
// vanish and the camera sees in, and from below (placement mode) the floor does.

import * as THREE from "three";
import type { RoomMesh } from "../sim/engine";

export type Surface = "floor" | "wall" | "ceiling";

/** Classifies a face by its inward unit normal's y component. */
export function surfaceOf(normalY: number): Surface {
  if (normalY > 0.7) return "floor";
  if (normalY < -0.2) return "ceiling";
  return "wall";
}

function floorTexture(): THREE.CanvasTexture {
  // Light oak planks, drawn once on a canvas.
  const canvas = document.createElement("canvas");
  canvas.width = 512;
  canvas.height = 512;
  const g = canvas.getContext("2d")!;
  const planks = 8;
  const h = canvas.height / planks;
  let seed = 7;
  const rand = () => ((seed = (seed * 16807) % 2147483647) / 2147483647);
  for (let i = 0; i < planks; i++) {
    const offset = rand() * canvas.width;
    for (let k = -1; k < 2; k++) {
      const tone = 150 + rand() * 40;
      g.fillStyle = `rgb(${tone + 40}, ${tone + 8}, ${tone - 40})`;
      g.fillRect(offset + k * canvas.width, i * h, canvas.width, h);
      g.fillStyle = "rgba(60, 35, 15, 0.55)";
      g.fillRect(offset + k * canvas.width, i * h, 2, h);
    }
    for (let s = 0; s < 40; s++) {
      g.strokeStyle = `rgba(90, 55, 25, ${0.05 + rand() * 0.08})`;
      g.beginPath();
      const y = i * h + rand() * h;
      g.moveTo(0, y);
      g.bezierCurveTo(170, y + rand() * 6 - 3, 340, y + rand() * 6 - 3, 512, y);
      g.stroke();
    }
    g.fillStyle = "rgba(50, 30, 12, 0.6)";
    g.fillRect(0, i * h, canvas.width, 2);
  }
  return repeatingTexture(canvas);
}

/** A drawn canvas as a colour texture that repeats both ways (planks, grain). */
export function repeatingTexture(canvas: HTMLCanvasElement): THREE.CanvasTexture {
  const texture = new THREE.CanvasTexture(canvas);
  texture.wrapS = THREE.RepeatWrapping;
  texture.wrapT = THREE.RepeatWrapping;
  texture.colorSpace = THREE.SRGBColorSpace;
  texture.anisotropy = 4;
  return texture;
}

/** Builds the room's meshes (one per surface kind) from the engine's triangles. */
export function buildRoom(room: RoomMesh): THREE.Group {
  const buckets: Record<Surface, number[]> = { floor: [], wall: [], ceiling: [] };
  const v = room.vertices;
  const a = new THREE.Vector3();
  const b = new THREE.Vector3();
  const c = new THREE.Vector3();
  const n = new THREE.Vector3();
  for (let t = 0; t < room.triangles.length; t += 3) {
    const [i, j, k] = [room.triangles[t], room.triangles[t + 1], room.triangles[t + 2]];
    a.fromArray(v, i * 3);
    b.fromArray(v, j * 3);
    c.fromArray(v, k * 3);
    n.subVectors(b, a).cross(c.clone().sub(a)).normalize();
    buckets[surfaceOf(n.y)].push(a.x, a.y, a.z, b.x, b.y, b.z, c.x, c.y, c.z);
  }

  const group = new THREE.Group();
  group.name = "room";
  const materials: Record<Surface, THREE.Material> = {
    floor: new THREE.MeshStandardMaterial({ map: floorTexture(), roughness: 0.55, metalness: 0 }),
    wall: new THREE.MeshStandardMaterial({ color: 0xe9e2d6, roughness: 0.9, metalness: 0 }),
    ceiling: new THREE.MeshStandardMaterial({ color: 0xf4efe6, roughness: 0.85, metalness: 0 }),
  };
  for (const surface of ["floor", "wall", "ceiling"] as Surface[]) {
    const positions = buckets[surface];
    if (positions.length === 0) continue;
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute("position", new THREE.Float32BufferAttribute(positions, 3));
    if (surface === "floor") {
      // Planar UVs: one texture tile per 2 m.
      const uv = [];
      for (let p = 0; p < positions.length; p += 3) uv.push(positions[p] / 2, positions[p + 2] / 2);
      geometry.setAttribute("uv", new THREE.Float32BufferAttribute(uv, 2));
    }
    geometry.computeVertexNormals();
    const mesh = new THREE.Mesh(geometry, materials[surface]);
    mesh.name = surface;
    mesh.receiveShadow = true;
    // Only the balloons cast shadows: the ceiling would otherwise shade the whole room.
    mesh.castShadow = false;
    group.add(mesh);
  }
  return group;
}
