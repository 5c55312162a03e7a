// Foil balloons: the engine's 18″ pillow (up_scene::foil_mesh, read through
// `write_model_mesh`), one InstancedMesh per foil model, metallic (metalness
// 1, low roughness: physics-reference "Looks") with a procedural crimp
// normal map, each instance tinted with its colour and dented like the latex
// ones (squash.ts). Only scenes with a foil group make one; the latex mesh
// draws their bodies at size 0.

import * as THREE from "three";
import type { ModelMesh } from "../sim/engine";
import { bodiesByFoilModel, gatherPoses } from "./foilRouting";
import { balloonInstances } from "./balloonInstances";
import { POSE_STRIDE, writeInstanceMatrices } from "./poseMath";
import { SQUASH_ATTRIBUTE, addSquash } from "./squash";

/** Texels across the crimp normal map. */
const CRIMP_TEXELS = 256;
/** Pleats around the rim, where the film crimps as it fills. */
const CRIMP_PLEATS = 44;

/** A deterministic pseudo-random sequence in [0, 1) (mulberry32): the same crimps every load. */
function random(seed: number): () => number {
  let a = seed >>> 0;
  return () => {
    a = (a + 0x6d2b79f5) >>> 0;
    let t = a;
    t = Math.imul(t ^ (t >>> 15), t | 1);
    t ^= t + Math.imul(t ^ (t >>> 7), t | 61);
    return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
  };
}

/**
 * A normal map of a filled foil disc seen face-on (uv centre: the disc's
 * centre): radial pleats that deepen toward the rim and a faint crinkle all
 * over, from a height field by central differences.
 */
function crimpNormalMap(): THREE.DataTexture {
  const n = CRIMP_TEXELS;
  const rnd = random(18);
  const phases = Array.from({ length: 6 }, () => rnd() * Math.PI * 2);
  const height = new Float32Array(n * n);
  for (let j = 0; j < n; j++) {
    for (let i = 0; i < n; i++) {
      const u = (i + 0.5) / n - 0.5;
      const v = (j + 0.5) / n - 0.5;
      const r = Math.hypot(u, v) * 2;
      const theta = Math.atan2(v, u);
      // Pleats wander a little so they do not look machined.
      const wobble = 0.18 * Math.sin(7 * theta + phases[0]) + 0.1 * Math.sin(13 * theta + 9 * r + phases[1]);
      const pleat = Math.abs(((((CRIMP_PLEATS * theta) / (2 * Math.PI) + wobble) % 1) + 1) % 1 * 2 - 1);
      const rim = Math.min(1, Math.max(0, (r - 0.55) / 0.4)) ** 2;
      const crinkle = 0.5 + 0.25 * Math.sin(41 * u + 17 * v + phases[2]) * Math.sin(23 * v - 37 * u + phases[3]);
      height[j * n + i] = rim * pleat + 0.06 * crinkle;
    }
  }
  const data = new Uint8Array(n * n * 4);
  const strength = 5;
  for (let j = 0; j < n; j++) {
    for (let i = 0; i < n; i++) {
      const h = (x: number, y: number) => height[Math.min(n - 1, Math.max(0, y)) * n + Math.min(n - 1, Math.max(0, x))];
      const dx = (h(i + 1, j) - h(i - 1, j)) * strength;
      const dy = (h(i, j + 1) - h(i, j - 1)) * strength;
      const len = Math.hypot(dx, dy, 1);
      const o = (j * n + i) * 4;
      data[o] = Math.round(((-dx / len) * 0.5 + 0.5) * 255);
      data[o + 1] = Math.round(((-dy / len) * 0.5 + 0.5) * 255);
      data[o + 2] = Math.round(((1 / len) * 0.5 + 0.5) * 255);
      data[o + 3] = 255;
    }
  }
  const texture = new THREE.DataTexture(data, n, n, THREE.RGBAFormat);
  texture.wrapS = texture.wrapT = THREE.ClampToEdgeWrapping;
  texture.magFilter = THREE.LinearFilter;
  texture.minFilter = THREE.LinearMipmapLinearFilter;
  texture.generateMipmaps = true;
  texture.needsUpdate = true;
  return texture;
}

/** The engine's surface as a geometry, with uv projected face-on (x, y across the disc) for the crimp map. */
function foilGeometry(mesh: ModelMesh): THREE.BufferGeometry {
  const g = new THREE.BufferGeometry();
  const p = mesh.positions;
  let extent = 0;
  for (let i = 0; i < p.length; i += 3) extent = Math.max(extent, Math.abs(p[i]), Math.abs(p[i + 1]));
  const uv = new Float32Array((p.length / 3) * 2);
  for (let v = 0; v < p.length / 3; v++) {
    uv[2 * v] = p[3 * v] / (2 * extent) + 0.5;
    uv[2 * v + 1] = p[3 * v + 1] / (2 * extent) + 0.5;
  }
  g.setAttribute("position", new THREE.BufferAttribute(p, 3));
  g.setAttribute("normal", new THREE.BufferAttribute(mesh.normals, 3));
  g.setAttribute("uv", new THREE.BufferAttribute(uv, 2));
  g.setIndex(new THREE.BufferAttribute(mesh.indices, 1));
  g.computeBoundingSphere();
  return g;
}

interface FoilModel {
  mesh: THREE.InstancedMesh;
  capacity: number;
  /** Dense indices of this model's bodies, instance order. */
  bodies: Uint32Array;
}

export class FoilBalloons {
  readonly group = new THREE.Group();
  private readonly material: THREE.MeshPhysicalMaterial;
  private readonly models: (FoilModel | null)[];
  private readonly isFoil: boolean[];
  private readonly scratchColor = new THREE.Color();
  /** Poses and sizes of one model's bodies in a row (foilRouting.gatherPoses). */
  private prev = new Float32Array(0);
  private curr = new Float32Array(0);
  private sizes = new Float32Array(0);

  /** `meshes`: per balloon model, its foil surface, or null for a latex model. */
  constructor(meshes: (ModelMesh | null)[]) {
    this.material = new THREE.MeshPhysicalMaterial({
      color: 0xffffff,
      metalness: 1,
      roughness: 0.15,
      normalMap: crimpNormalMap(),
      normalScale: new THREE.Vector2(0.6, 0.6),
      envMapIntensity: 1,
    });
    addSquash(this.material);
    this.isFoil = meshes.map((m) => m !== null);
    this.models = meshes.map((m) => (m ? this.makeModel(foilGeometry(m), 16) : null));
  }

  private makeModel(geometry: THREE.BufferGeometry, capacity: number, old?: FoilModel): FoilModel {
    if (old) {
      this.group.remove(old.mesh);
      old.mesh.dispose();
    }
    const squash = new THREE.InstancedBufferAttribute(new Float32Array(capacity * 4), 4);
    squash.setUsage(THREE.DynamicDrawUsage);
    geometry.setAttribute(SQUASH_ATTRIBUTE, squash);
    const mesh = balloonInstances(geometry, this.material, capacity, "foil-balloons");
    this.group.add(mesh);
    return { mesh, capacity, bodies: new Uint32Array(0) };
  }

  /** New bodies or a new order: which bodies each foil mesh draws, and their tints. */
  setBodies(colors: Uint32Array, models: Uint32Array, palette: THREE.Color[]): void {
    const lists = bodiesByFoilModel(models, this.isFoil);
    let most = 0;
    this.models.forEach((model, m) => {
      if (!model) return;
      const bodies = lists[m];
      if (bodies.length > model.capacity) {
        model = this.makeModel(model.mesh.geometry, Math.max(bodies.length, model.capacity * 2), model);
        this.models[m] = model;
      }
      model.bodies = bodies;
      for (let k = 0; k < bodies.length; k++) {
        model.mesh.setColorAt(k, palette[colors[bodies[k]]] ?? this.scratchColor.set(1, 1, 1));
      }
      if (model.mesh.instanceColor) model.mesh.instanceColor.needsUpdate = true;
      model.mesh.count = bodies.length;
      most = Math.max(most, bodies.length);
    });
    if (most > this.sizes.length) {
      this.prev = new Float32Array(most * POSE_STRIDE);
      this.curr = new Float32Array(most * POSE_STRIDE);
      this.sizes = new Float32Array(most);
    }
  }

  /**
   * Interpolated poses at each body's size now, as the latex balloons (the
   * mesh is already the model's size), and each body's dent from `squash`
   * (four floats per body, dense order) when given.
   */
  update(prev: Float32Array, curr: Float32Array, alpha: number, bodyScales: Float32Array, squash?: Float32Array): void {
    for (const model of this.models) {
      if (!model) continue;
      const n = gatherPoses(prev, bodyScales, model.bodies, this.prev, this.sizes);
      gatherPoses(curr, bodyScales, model.bodies, this.curr, this.sizes);
      writeInstanceMatrices(model.mesh.instanceMatrix.array as Float32Array, this.prev, this.curr, n, alpha, this.sizes);
      model.mesh.count = n;
      model.mesh.instanceMatrix.clearUpdateRanges();
      model.mesh.instanceMatrix.addUpdateRange(0, n * 16);
      model.mesh.instanceMatrix.needsUpdate = true;
      const dents = model.mesh.geometry.getAttribute(SQUASH_ATTRIBUTE) as THREE.InstancedBufferAttribute | undefined;
      if (squash && dents) {
        const out = dents.array as Float32Array;
        for (let k = 0; k < n; k++) for (let c = 0; c < 4; c++) out[4 * k + c] = squash[4 * model.bodies[k] + c] ?? 0;
        dents.clearUpdateRanges();
        dents.addUpdateRange(0, n * 4);
        dents.needsUpdate = true;
      }
    }
  }

  /** Foil balloons drawn, all foil models together. */
  get count(): number {
    return this.models.reduce((sum, m) => sum + (m ? m.mesh.count : 0), 0);
  }

  dispose(): void {
    for (const model of this.models) {
      if (!model) continue;
      model.mesh.geometry.dispose();
      model.mesh.dispose();
    }
    this.material.normalMap?.dispose();
    this.material.dispose();
  }
}
