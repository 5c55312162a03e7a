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
import { normalMapFromHeight, seededRandom } from "./normalMap";

/** Texels across the crimp normal map. */
const CRIMP_TEXELS = 256;
/** Pleats around the rim, where the film crimps as it fills. */
const CRIMP_PLEATS = 44;

/**
 * A normal map of a filled foil disc seen face-on (uv centre: the disc's
 * centre): radial pleats that deepen toward the rim and a faint crinkle all
 * over, from a height field by central differences.
 */
function crimpNormalMap(): THREE.DataTexture {
  const rnd = seededRandom(18);
  const phases = Array.from({ length: 6 }, () => rnd() * Math.PI * 2);
  const height = (s: number, t: number) => {
    const u = s - 0.5;
    const v = t - 0.5;
    const r = Math.hypot(u, v) * 2;
    const theta = Math.atan2(v, u);
    // Pleats wander a little so they do not look machined.
    const wobble = 0.18 * Math.sin(7 * theta + phases[0]) + 0.1 * Math.sin(13 * theta + 9 * r + phases[1]);
    const pleat = Math.abs(((((CRIMP_PLEATS * theta) / (2 * Math.PI) + wobble) % 1) + 1) % 1 * 2 - 1);
    const rim = Math.min(1, Math.max(0, (r - 0.55) / 0.4)) ** 2;
    const crinkle = 0.5 + 0.25 * Math.sin(41 * u + 17 * v + phases[2]) * Math.sin(23 * v - 37 * u + phases[3]);
    return rim * pleat + 0.06 * crinkle;
  };
  return normalMapFromHeight(height, 5, CRIMP_TEXELS, false);
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
