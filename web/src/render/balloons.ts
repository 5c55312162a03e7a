// The balloons: one InstancedMesh of assets/balloon.obj, shiny latex
// (MeshPhysicalMaterial with clearcoat and sheen, lit by the environment
// map), each instance tinted with its colour from the per-colour MTL files.
// Poses go straight from the worker's frame into `instanceMatrix.array`.
// Balloons of foil groups are drawn by FoilBalloons (foilBalloons.ts) with
// the engine's foil pillow; the latex mesh draws them at size 0.

import * as THREE from "three";
import { OBJLoader } from "three/examples/jsm/loaders/OBJLoader.js";
import { mergeGeometries, mergeVertices } from "three/examples/jsm/utils/BufferGeometryUtils.js";
import { colorNameOfMtlFile, parseMtl } from "./mtl";
import { writeInstanceMatrices } from "./poseMath";
import { CROWD_BALLOONS, revolutionProfile, thinProfile } from "./crowdLod";
import { FoilBalloons } from "./foilBalloons";
import { balloonInstances } from "./balloonInstances";
import type { ModelMesh } from "../sim/engine";

/** Rings kept (every n-th) and segments around of the crowd geometry: 20 × 12, about 450 triangles. */
const CROWD_RING_STEP = 2;
const CROWD_SEGMENTS = 12;

export interface BalloonAssets {
  geometry: THREE.BufferGeometry;
  /** The same balloon with fewer triangles, for crowds (crowdLod.ts). */
  crowdGeometry: THREE.BufferGeometry;
  /** Widest horizontal extent of the OBJ, m: the model's diameter. */
  diameter: number;
  /** Linear RGB of each colour name found in the MTL files. */
  mtlColors: Map<string, [number, number, number]>;
}

/** Loads the balloon OBJ and the per-colour MTL files listed in the asset manifest. */
export async function loadBalloonAssets(base: string): Promise<BalloonAssets> {
  const manifestResponse = await fetch(`${base}manifest.json`);
  if (!manifestResponse.ok) throw new Error(`cannot load ${base}manifest.json: HTTP ${manifestResponse.status}`);
  const manifest = (await manifestResponse.json()) as { files: string[] };
  const objFile = manifest.files.find((f) => /(^|\/)balloon\.obj$/i.test(f)) ?? manifest.files.find((f) => f.endsWith(".obj"));
  if (!objFile) throw new Error("the balloon model (assets/balloon.obj) is missing");
  const objResponse = await fetch(base + objFile);
  if (!objResponse.ok) throw new Error(`cannot load ${objFile}: HTTP ${objResponse.status}`);
  const group = new OBJLoader().parse(await objResponse.text());

  const parts: THREE.BufferGeometry[] = [];
  group.traverse((o) => {
    if ((o as THREE.Mesh).isMesh) {
      const g = (o as THREE.Mesh).geometry.clone();
      g.deleteAttribute("uv");
      for (const name of Object.keys(g.attributes)) if (name !== "position" && name !== "normal") g.deleteAttribute(name);
      parts.push(g);
    }
  });
  if (parts.length === 0) throw new Error(`${objFile} has no faces`);
  let geometry = parts.length === 1 ? parts[0] : mergeGeometries(parts, false)!;
  // Welded vertices give smooth normals: latex has no facets.
  geometry.deleteAttribute("normal");
  geometry = mergeVertices(geometry, 1e-5);
  geometry.computeVertexNormals();
  geometry.computeBoundingBox();
  geometry.computeBoundingSphere();
  const box = geometry.boundingBox!;
  const diameter = Math.max(box.max.x - box.min.x, box.max.z - box.min.z);
  const profile = thinProfile(revolutionProfile(geometry.getAttribute("position").array), CROWD_RING_STEP);
  const crowdGeometry = new THREE.LatheGeometry(
    profile.map(([r, y]) => new THREE.Vector2(r, y)),
    CROWD_SEGMENTS,
  );
  crowdGeometry.deleteAttribute("uv");
  crowdGeometry.computeBoundingSphere();

  const mtlColors = new Map<string, [number, number, number]>();
  await Promise.all(
    manifest.files
      .filter((f) => f.endsWith(".mtl"))
      .map(async (f) => {
        const response = await fetch(base + f);
        if (!response.ok) return;
        const materials = parseMtl(await response.text());
        const name = colorNameOfMtlFile(f);
        const kd = materials.find((m) => m.kd)?.kd;
        if (name && kd) mtlColors.set(name, kd);
      }),
  );
  return { geometry, crowdGeometry, diameter, mtlColors };
}

export class Balloons {
  readonly group = new THREE.Group();
  private mesh: THREE.InstancedMesh;
  private readonly material: THREE.MeshPhysicalMaterial;
  private capacity = 0;
  /** Scale of each instance's model (model diameter / OBJ diameter). */
  private scales = new Float32Array(0);
  /** Scale of each instance as drawn: its model's times its body's size now (the gas's). */
  private drawnScales = new Float32Array(0);
  private modelScale: number[] = [1];
  /** The foil balloons, when the world has a foil group. */
  foil: FoilBalloons | null = null;
  private palette: THREE.Color[] = [];
  private readonly scratchColor = new THREE.Color();

  constructor(private readonly assets: BalloonAssets) {
    this.material = new THREE.MeshPhysicalMaterial({
      color: 0xffffff,
      roughness: 0.38,
      metalness: 0,
      // Latex: a glossy film over a soft, slightly velvety body.
      clearcoat: 0.9,
      clearcoatRoughness: 0.08,
      sheen: 0.12,
      sheenRoughness: 0.5,
      sheenColor: new THREE.Color(0xffffff),
      specularIntensity: 0.5,
      envMapIntensity: 0.9,
    });
    this.mesh = this.makeMesh(256);
  }

  private makeMesh(capacity: number): THREE.InstancedMesh {
    if (this.mesh) {
      this.group.remove(this.mesh);
      this.mesh.dispose();
    }
    const mesh = balloonInstances(this.assets.geometry, this.material, capacity, "balloons");
    this.group.add(mesh);
    this.capacity = capacity;
    this.scales = new Float32Array(capacity);
    this.drawnScales = new Float32Array(capacity);
    this.mesh = mesh;
    return mesh;
  }

  /**
   * Colours by index (MTL Kd when the name has a file, else the engine's
   * RGB), model sizes, and each foil model's surface (null: latex).
   */
  setWorld(palette: [number, number, number][], colorNames: string[], diameters: number[], foilMeshes: (ModelMesh | null)[]): void {
    this.palette = palette.map((rgb, i) => {
      const fromMtl = this.assets.mtlColors.get(colorNames[i]?.toLowerCase() ?? "");
      const [r, g, b] = fromMtl ?? rgb;
      // MTL Kd (and the engine's palette) are display sRGB, as three's MTLLoader reads them.
      return new THREE.Color().setRGB(r, g, b, THREE.SRGBColorSpace);
    });
    // A zero scale draws nothing: a foil body's latex instance stays in place, so the latex path is unchanged.
    this.modelScale = diameters.map((d, m) => (foilMeshes[m] ? 0 : d / this.assets.diameter));
    if (this.foil) {
      this.group.remove(this.foil.group);
      this.foil.dispose();
      this.foil = null;
    }
    if (foilMeshes.some((m) => m !== null)) {
      this.foil = new FoilBalloons(foilMeshes);
      this.group.add(this.foil.group);
    }
  }

  /** New bodies or a new order: re-tint every instance. */
  setBodies(colors: Uint32Array, models: Uint32Array): void {
    const count = colors.length;
    if (count > this.capacity) this.makeMesh(Math.max(count, this.capacity * 2));
    for (let i = 0; i < count; i++) {
      this.mesh.setColorAt(i, this.palette[colors[i]] ?? this.scratchColor.set(1, 1, 1));
      this.scales[i] = this.modelScale[models[i]] ?? 1;
    }
    if (this.mesh.instanceColor) this.mesh.instanceColor.needsUpdate = true;
    this.mesh.count = count;
    this.mesh.geometry = count > CROWD_BALLOONS ? this.assets.crowdGeometry : this.assets.geometry;
    this.foil?.setBodies(colors, models, this.palette);
  }

  /**
   * Writes interpolated poses into the instance matrices, each scaled by its
   * body's size now (`bodyScales`, one per body; 1 where it is short): the
   * pose is the mesh frame's origin, so translate · rotate · scale draws a
   * shrunken balloon where the engine has it.
   */
  update(prev: Float32Array, curr: Float32Array, count: number, alpha: number, bodyScales: Float32Array): void {
    const n = Math.min(count, this.capacity);
    const drawn = this.drawnScales;
    for (let i = 0; i < n; i++) drawn[i] = this.scales[i] * (i < bodyScales.length ? bodyScales[i] : 1);
    writeInstanceMatrices(this.mesh.instanceMatrix.array as Float32Array, prev, curr, n, alpha, drawn);
    this.mesh.count = n;
    this.mesh.instanceMatrix.clearUpdateRanges();
    this.mesh.instanceMatrix.addUpdateRange(0, n * 16);
    this.mesh.instanceMatrix.needsUpdate = true;
    this.foil?.update(prev, curr, alpha, bodyScales);
  }

  get count(): number {
    return this.mesh.count;
  }

  setVisible(visible: boolean): void {
    this.group.visible = visible;
  }
}
