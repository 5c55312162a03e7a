// The bake: the live scene as the path tracer can take it. The tracer reads
// plain meshes only (no InstancedMesh, no vertices placed by a shader), so
// each InstancedMesh becomes one merged mesh with its instances' colours as
// vertex colours, the ribbons' strips are computed on the CPU
// (ribbonStrip.ts), and plain meshes (the room) are copied in world space.
// Materials are clones of the live ones at bake time, so the photo shows the
// same finishes as the live view, less any shader edits of their own.

import * as THREE from "three";
import { STRIP_VERTICES, stripIndices, writeRibbonStrip, type RibbonRow } from "./ribbonStrip";

/** A merged mesh's arrays. */
export interface MeshArrays {
  positions: Float32Array;
  normals: Float32Array;
  /** Linear RGB per vertex, or null when the instances carry no colour. */
  colors: Float32Array | null;
  indices: Uint32Array;
}

/** An instance whose matrix has a determinant below this draws nothing (a foil body's latex instance, at scale 0). */
const EMPTY_INSTANCE_DET = 1e-15;

/**
 * `count` copies of a geometry (`positions`, `normals`, 3 floats a vertex;
 * `index`, or null for a triangle list), each moved by its column-major 4×4
 * matrix in `matrices` (16 floats an instance, as `InstancedMesh.instanceMatrix`)
 * and coloured by its RGB in `instanceColors` (3 floats an instance, or null).
 * Normals go through the matrix's cofactor (its inverse transpose up to a
 * scale), so a stretched instance keeps them perpendicular. Instances of
 * zero scale are left out.
 */
export function bakeInstances(
  positions: ArrayLike<number>,
  normals: ArrayLike<number>,
  index: ArrayLike<number> | null,
  matrices: ArrayLike<number>,
  count: number,
  instanceColors: ArrayLike<number> | null,
): MeshArrays {
  const vertices = positions.length / 3;
  const triangleIndex = index ?? Array.from({ length: vertices }, (_, i) => i);
  const kept: number[] = [];
  for (let i = 0; i < count; i++) if (Math.abs(det3(matrices, i * 16)) > EMPTY_INSTANCE_DET) kept.push(i);
  const outPositions = new Float32Array(kept.length * vertices * 3);
  const outNormals = new Float32Array(kept.length * vertices * 3);
  const outColors = instanceColors ? new Float32Array(kept.length * vertices * 3) : null;
  const outIndices = new Uint32Array(kept.length * triangleIndex.length);
  const cof = new Float64Array(9);
  kept.forEach((instance, k) => {
    const m = instance * 16;
    const e = (i: number) => matrices[m + i];
    const sign = det3(matrices, m) < 0 ? -1 : 1;
    // Cofactor matrix of the upper 3×3 (column-major a_ij = e(j*4+i)).
    const a = (r: number, c: number) => e(c * 4 + r);
    for (let r = 0; r < 3; r++) {
      for (let c = 0; c < 3; c++) {
        const r1 = (r + 1) % 3;
        const r2 = (r + 2) % 3;
        const c1 = (c + 1) % 3;
        const c2 = (c + 2) % 3;
        cof[r * 3 + c] = sign * (a(r1, c1) * a(r2, c2) - a(r1, c2) * a(r2, c1));
      }
    }
    const base = k * vertices;
    for (let v = 0; v < vertices; v++) {
      const x = positions[v * 3];
      const y = positions[v * 3 + 1];
      const z = positions[v * 3 + 2];
      const o = (base + v) * 3;
      outPositions[o] = e(0) * x + e(4) * y + e(8) * z + e(12);
      outPositions[o + 1] = e(1) * x + e(5) * y + e(9) * z + e(13);
      outPositions[o + 2] = e(2) * x + e(6) * y + e(10) * z + e(14);
      const nx = normals[v * 3];
      const ny = normals[v * 3 + 1];
      const nz = normals[v * 3 + 2];
      const tx = cof[0] * nx + cof[1] * ny + cof[2] * nz;
      const ty = cof[3] * nx + cof[4] * ny + cof[5] * nz;
      const tz = cof[6] * nx + cof[7] * ny + cof[8] * nz;
      const l = Math.hypot(tx, ty, tz) || 1;
      outNormals[o] = tx / l;
      outNormals[o + 1] = ty / l;
      outNormals[o + 2] = tz / l;
      if (outColors && instanceColors) {
        outColors[o] = instanceColors[instance * 3];
        outColors[o + 1] = instanceColors[instance * 3 + 1];
        outColors[o + 2] = instanceColors[instance * 3 + 2];
      }
    }
    const ti = k * triangleIndex.length;
    for (let t = 0; t < triangleIndex.length; t++) outIndices[ti + t] = base + triangleIndex[t];
  });
  return { positions: outPositions, normals: outNormals, colors: outColors, indices: outIndices };
}

/** Determinant of the upper 3×3 of the column-major 4×4 matrix at `m`. */
function det3(e: ArrayLike<number>, m: number): number {
  return (
    e[m] * (e[m + 5] * e[m + 10] - e[m + 9] * e[m + 6]) -
    e[m + 4] * (e[m + 1] * e[m + 10] - e[m + 9] * e[m + 2]) +
    e[m + 8] * (e[m + 1] * e[m + 6] - e[m + 5] * e[m + 2])
  );
}

/**
 * RGB colours as RGBA (alpha 1): the tracer fills a mesh without colours
 * with RGBA white and merges every mesh's colours into one array, so
 * colours of three components would shift every mesh's after them.
 */
export function rgba(rgb: ArrayLike<number>, itemSize: number): Float32Array {
  if (itemSize === 4) return Float32Array.from(rgb);
  const n = Math.floor(rgb.length / itemSize);
  const out = new Float32Array(n * 4).fill(1);
  for (let i = 0; i < n; i++) for (let c = 0; c < Math.min(3, itemSize); c++) out[i * 4 + c] = rgb[i * itemSize + c];
  return out;
}

function geometryOf(arrays: MeshArrays): THREE.BufferGeometry {
  const g = new THREE.BufferGeometry();
  g.setAttribute("position", new THREE.BufferAttribute(arrays.positions, 3));
  g.setAttribute("normal", new THREE.BufferAttribute(arrays.normals, 3));
  if (arrays.colors) g.setAttribute("color", new THREE.BufferAttribute(rgba(arrays.colors, 3), 4));
  g.setIndex(new THREE.BufferAttribute(arrays.indices, 1));
  g.computeBoundingSphere();
  return g;
}

/**
 * A copy of a live material for the photo: the same surface, without the
 * live view's shader edits (they place vertices the bake has already placed).
 */
function photoMaterial(live: THREE.Material, vertexColors: boolean): THREE.Material {
  const m = live.clone();
  m.onBeforeCompile = () => {};
  m.customProgramCacheKey = () => "";
  m.vertexColors = vertexColors || m.vertexColors;
  return m;
}

/** The ribbons as the live view draws them now. */
export interface RibbonSource {
  /** The live view's ribbon mesh: its `ribbon` and `color` instance attributes say where and what colour. */
  mesh: THREE.Mesh;
  /** The points drawn now, RGBA (4 floats a point), as the live view's points texture. */
  texels: Float32Array;
  halfWidth: number;
}

/** What a bake made, and what it took. */
export interface Bake {
  scene: THREE.Scene;
  /** Balloons, ribbons and weights: instances baked into meshes. */
  instances: number;
  triangles: number;
  dispose(): void;
}

/** Whether `o` is one of `roots` or inside one. */
function inside(o: THREE.Object3D, roots: THREE.Object3D[]): boolean {
  for (let p: THREE.Object3D | null = o; p; p = p.parent) if (roots.includes(p)) return true;
  return false;
}

/** Whether `o` and every parent are visible. */
function shown(o: THREE.Object3D): boolean {
  for (let p: THREE.Object3D | null = o; p; p = p.parent) if (!p.visible) return false;
  return true;
}

/**
 * Bakes the visible meshes of `live` (but those under `exclude`) into a new
 * scene of plain meshes in world space; `ribbons`, when given, are baked
 * from their points instead of their shader-placed template.
 */
export function bakeScene(live: THREE.Scene, exclude: THREE.Object3D[], ribbons: RibbonSource | null): Bake {
  live.updateMatrixWorld(true);
  const scene = new THREE.Scene();
  const owned: { dispose(): void }[] = [];
  let instances = 0;
  let triangles = 0;
  const addMesh = (arrays: MeshArrays, material: THREE.Material, name: string) => {
    if (arrays.indices.length === 0) return;
    const geometry = geometryOf(arrays);
    const mesh = new THREE.Mesh(geometry, material);
    mesh.name = name;
    scene.add(mesh);
    owned.push(geometry, material);
    triangles += arrays.indices.length / 3;
  };
  const meshes: THREE.Mesh[] = [];
  live.traverse((o) => {
    if ((o as THREE.Mesh).isMesh && shown(o) && !inside(o, exclude)) meshes.push(o as THREE.Mesh);
  });
  for (const mesh of meshes) {
    const material = Array.isArray(mesh.material) ? mesh.material[0] : mesh.material;
    const geometry = mesh.geometry;
    const position = geometry.getAttribute("position");
    if (ribbons && mesh === ribbons.mesh) {
      const arrays = bakeRibbons(ribbons);
      instances += arrays.ribbons;
      addMesh(arrays, photoMaterial(material, true), mesh.name);
      continue;
    }
    // Vertices placed by a shader of its own: nothing on the CPU says where they are.
    if ((geometry as THREE.InstancedBufferGeometry).isInstancedBufferGeometry || !position) continue;
    if (!geometry.getAttribute("normal")) geometry.computeVertexNormals();
    const normal = geometry.getAttribute("normal");
    const index = geometry.getIndex()?.array ?? null;
    const inst = mesh as THREE.InstancedMesh;
    if (inst.isInstancedMesh) {
      if (inst.count === 0) continue;
      // The instances' matrices are in the mesh's frame: bring them to the world.
      const matrices = new Float32Array(inst.count * 16);
      const m = new THREE.Matrix4();
      for (let i = 0; i < inst.count; i++) {
        inst.getMatrixAt(i, m);
        m.premultiply(inst.matrixWorld).toArray(matrices, i * 16);
      }
      const colors = inst.instanceColor ? (inst.instanceColor.array as Float32Array) : null;
      const arrays = bakeInstances(position.array, normal.array, index, matrices, inst.count, colors);
      instances += arrays.positions.length / Math.max(1, position.array.length);
      addMesh(arrays, photoMaterial(material, !!colors), mesh.name);
    } else {
      const arrays = bakeInstances(position.array, normal.array, index, mesh.matrixWorld.elements, 1, null);
      const copy = geometryOf(arrays);
      // Keep the uv (the floor's planks) and the vertex colours a plain mesh has.
      const uv = geometry.getAttribute("uv");
      if (uv) copy.setAttribute("uv", uv.clone());
      const color = geometry.getAttribute("color");
      if (color) copy.setAttribute("color", new THREE.BufferAttribute(rgba(color.array, color.itemSize), 4));
      const baked = new THREE.Mesh(copy, photoMaterial(material, false));
      baked.name = mesh.name;
      scene.add(baked);
      owned.push(copy, baked.material as THREE.Material);
      triangles += arrays.indices.length / 3;
    }
  }
  return {
    scene,
    instances,
    triangles,
    dispose: () => owned.forEach((o) => o.dispose()),
  };
}

/** Every ribbon of `source` as one mesh of strips, in its colour. */
export function bakeRibbons(source: RibbonSource): MeshArrays & { ribbons: number } {
  const geometry = source.mesh.geometry as THREE.InstancedBufferGeometry;
  const rows = geometry.getAttribute("ribbon");
  const colors = geometry.getAttribute("color");
  const n = Math.min(geometry.instanceCount, rows?.count ?? 0);
  const positions = new Float32Array(n * STRIP_VERTICES * 3);
  const normals = new Float32Array(n * STRIP_VERTICES * 3);
  const vertexColors = new Float32Array(n * STRIP_VERTICES * 3);
  const points = source.texels.length / 4;
  let drawn = 0;
  for (let r = 0; r < n; r++) {
    const row: RibbonRow = { first: rows.getX(r), count: rows.getY(r), length: rows.getZ(r), phase: rows.getW(r) };
    if (row.count < 2 || row.first + row.count > points) continue;
    writeRibbonStrip(source.texels, row, source.halfWidth, positions, normals, drawn * STRIP_VERTICES);
    for (let v = 0; v < STRIP_VERTICES; v++) {
      const o = (drawn * STRIP_VERTICES + v) * 3;
      vertexColors[o] = colors ? colors.getX(r) : 1;
      vertexColors[o + 1] = colors ? colors.getY(r) : 1;
      vertexColors[o + 2] = colors ? colors.getZ(r) : 1;
    }
    drawn++;
  }
  const used = drawn * STRIP_VERTICES * 3;
  return {
    positions: positions.subarray(0, used),
    normals: normals.subarray(0, used),
    colors: vertexColors.subarray(0, used),
    indices: stripIndices(drawn),
    ribbons: drawn,
  };
}
