// The balloons: an InstancedMesh of assets/balloon.obj (baked at build time:
// balloonMeshFile.ts) per finish drawn
// (finishes.ts: latex, pearl, foil; MeshPhysicalMaterial lit by the
// environment map), each instance tinted with its colour from the per-colour
// MTL files. Every mesh holds every body in dense order and draws those of
// other finishes at size 0, so poses go straight from the worker's frame into
// each `instanceMatrix.array` and one squash attribute (squash.ts) serves them
// all; a scene of one finish has one mesh. Balloons of foil groups are drawn
// by FoilBalloons (foilBalloons.ts) with the engine's foil pillow; the latex
// meshes draw them at size 0.

import * as THREE from "three";
import { BALLOON_MESH_FILE, decodeBalloonMesh, type BalloonMesh } from "./balloonMeshFile";
import { writeInstanceMatrices } from "./poseMath";
import { CROWD_BALLOONS, revolutionProfile, thinProfile } from "./crowdLod";
import { FoilBalloons } from "./foilBalloons";
import { balloonInstances } from "./balloonInstances";
import { FinishMaterials, addLatexUv } from "./finishes";
import { SQUASH_ATTRIBUTE, SquashDents, addSquash } from "./squash";
import type { Finish, ModelMesh } from "../sim/engine";

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

/** The balloon model's file (balloonMeshFile.ts) under `base`, fetched at once; index.html preloads it. */
export async function fetchBalloonMesh(base: string): Promise<BalloonMesh> {
  const response = await fetch(base + BALLOON_MESH_FILE);
  if (!response.ok) throw new Error(`cannot load ${base}${BALLOON_MESH_FILE}: HTTP ${response.status}`);
  return decodeBalloonMesh(await response.arrayBuffer());
}

/** The balloon's geometries and colours from its baked mesh. */
export function balloonAssetsOf(mesh: BalloonMesh): BalloonAssets {
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute("position", new THREE.BufferAttribute(mesh.positions, 3));
  geometry.setAttribute("normal", new THREE.BufferAttribute(mesh.normals, 3));
  geometry.setIndex(new THREE.BufferAttribute(mesh.index, 1));
  geometry.computeBoundingBox();
  geometry.computeBoundingSphere();
  const box = geometry.boundingBox!;
  const diameter = Math.max(box.max.x - box.min.x, box.max.z - box.min.z);
  const profile = thinProfile(revolutionProfile(mesh.positions), CROWD_RING_STEP);
  const crowdGeometry = new THREE.LatheGeometry(
    profile.map(([r, y]) => new THREE.Vector2(r, y)),
    CROWD_SEGMENTS,
  );
  crowdGeometry.computeBoundingSphere();
  // The finishes' normal maps (neck pleats, knot, creases) need the same uv on both.
  addLatexUv(geometry);
  addLatexUv(crowdGeometry);
  return { geometry, crowdGeometry, diameter, mtlColors: new Map(Object.entries(mesh.colors)) };
}

/** Loads the balloon model and its colours (one baked file: balloonMeshFile.ts). */
export async function loadBalloonAssets(base: string): Promise<BalloonAssets> {
  return balloonAssetsOf(await fetchBalloonMesh(base));
}

/**
 * Share of its volume a latex balloon has lost when it comes down: an 11″
 * balloon lands with about 45 % left (its envelope outweighs the lift of the
 * rest). The latex's velvet (finishes.ts) is full by then.
 */
const VOLUME_LOST_WHEN_LANDED = 0.55;

/** A mesh of the latex balloon in one finish, holding every body. */
interface FinishMesh {
  finish: Finish;
  mesh: THREE.InstancedMesh;
  /** Scale of each instance as drawn: 0 for bodies of other finishes. */
  drawn: Float32Array;
}

/** The latex-shape finish of each model: the override, else the scene's; null for a foil model (its pillow is foil). */
export function modelFinishes(sceneFinishes: readonly Finish[], foil: readonly boolean[], override: Finish | null): (Finish | null)[] {
  return sceneFinishes.map((f, m) => (foil[m] ? null : (override ?? f)));
}

export class Balloons {
  readonly group = new THREE.Group();
  readonly materials = new FinishMaterials((m) => addSquash(m));
  private meshes: FinishMesh[] = [];
  private capacity = 256;
  /** Scale of each instance's model (model diameter / OBJ diameter). */
  private scales = new Float32Array(0);
  /** Each body's finish index into `meshes` (-1: a foil body, drawn by FoilBalloons). */
  private bodyMesh = new Int16Array(0);
  private modelScale: number[] = [1];
  private sceneFinishes: Finish[] = [];
  private isFoil: boolean[] = [];
  private modelFinish: (Finish | null)[] = [];
  /** The panel's finish for every latex balloon; null: as the scene says. */
  private override: Finish | null = null;
  /** The bodies last set, to re-route them when the finishes change. */
  private colors: Uint32Array = new Uint32Array(0);
  private models: Uint32Array = new Uint32Array(0);
  /** Every instance's dent now (squash.ts), shared by every mesh's geometry. */
  private squash: THREE.InstancedBufferAttribute;
  readonly dents = new SquashDents();
  /** The foil balloons, when the world has a foil group. */
  foil: FoilBalloons | null = null;
  private palette: THREE.Color[] = [];
  private readonly scratchColor = new THREE.Color();
  private drawnCount = 0;
  /** Balloons above which the crowd geometry draws them (a small device's page lowers it: drawingBudget.ts). */
  private crowdAbove = CROWD_BALLOONS;

  constructor(private readonly assets: BalloonAssets) {
    this.squash = this.makeSquash(this.capacity);
  }

  private makeSquash(capacity: number): THREE.InstancedBufferAttribute {
    const attribute = new THREE.InstancedBufferAttribute(new Float32Array(capacity * 4), 4);
    attribute.setUsage(THREE.DynamicDrawUsage);
    this.assets.geometry.setAttribute(SQUASH_ATTRIBUTE, attribute);
    this.assets.crowdGeometry.setAttribute(SQUASH_ATTRIBUTE, attribute);
    return attribute;
  }

  /** One mesh per finish the models draw, each of `capacity` instances. */
  private makeMeshes(): void {
    for (const m of this.meshes) {
      this.group.remove(m.mesh);
      m.mesh.dispose();
    }
    const wanted = [...new Set(this.modelFinish.filter((f): f is Finish => f !== null))];
    this.meshes = wanted.map((finish) => {
      const mesh = balloonInstances(this.assets.geometry, this.materials.get(finish), this.capacity, "balloons");
      mesh.userData.finish = finish;
      this.group.add(mesh);
      return { finish, mesh, drawn: new Float32Array(this.capacity) };
    });
  }

  /**
   * Colours by index (MTL Kd when the name has a file, else the engine's
   * RGB), model sizes, each model's finish, and each foil model's surface (null: latex).
   */
  setWorld(palette: [number, number, number][], colorNames: string[], diameters: number[], foilMeshes: (ModelMesh | null)[], finishes: Finish[] = []): void {
    this.palette = palette.map((rgb, i) => {
      const fromMtl = this.assets.mtlColors.get(colorNames[i]?.toLowerCase() ?? "");
      const [r, g, b] = fromMtl ?? rgb;
      // MTL Kd (and the engine's palette) are display sRGB, as three's MTLLoader reads them.
      return new THREE.Color().setRGB(r, g, b, THREE.SRGBColorSpace);
    });
    // A zero scale draws nothing: a foil body's latex instance stays in place, so the latex path is unchanged.
    this.modelScale = diameters.map((d, m) => (foilMeshes[m] ? 0 : d / this.assets.diameter));
    this.isFoil = diameters.map((_, m) => foilMeshes[m] !== null && foilMeshes[m] !== undefined);
    this.sceneFinishes = diameters.map((_, m) => finishes[m] ?? (this.isFoil[m] ? "foil" : "latex"));
    this.modelFinish = modelFinishes(this.sceneFinishes, this.isFoil, this.override);
    this.makeMeshes();
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

  /** Draws every latex balloon in `finish`, or (null) in its scene's. */
  setFinishOverride(finish: Finish | null): void {
    if (finish === this.override) return;
    this.override = finish;
    this.modelFinish = modelFinishes(this.sceneFinishes, this.isFoil, finish);
    this.makeMeshes();
    this.setBodies(this.colors, this.models);
  }

  /** Draws with the crowd geometry above `count` balloons from now on. */
  setCrowdAbove(count: number): void {
    this.crowdAbove = count;
    for (const { mesh } of this.meshes) mesh.geometry = mesh.count > count ? this.assets.crowdGeometry : this.assets.geometry;
  }

  /** Whether the crowd geometry draws the balloons now. */
  get crowdDrawn(): boolean {
    return this.meshes.some(({ mesh }) => mesh.geometry === this.assets.crowdGeometry);
  }

  get finishOverride(): Finish | null {
    return this.override;
  }

  /** New bodies or a new order: re-tint and re-route every instance. */
  setBodies(colors: Uint32Array, models: Uint32Array): void {
    this.colors = colors;
    this.models = models;
    const count = colors.length;
    if (count > this.capacity || this.scales.length < this.capacity) {
      this.capacity = Math.max(count, this.capacity * (count > this.capacity ? 2 : 1));
      this.squash = this.makeSquash(this.capacity);
      this.makeMeshes();
      this.scales = new Float32Array(this.capacity);
      this.bodyMesh = new Int16Array(this.capacity);
    }
    const meshOf = new Map(this.meshes.map((m, k) => [m.finish, k]));
    for (let i = 0; i < count; i++) {
      const model = models[i];
      this.scales[i] = this.modelScale[model] ?? 1;
      const finish = this.modelFinish[model] ?? null;
      this.bodyMesh[i] = finish === null ? -1 : (meshOf.get(finish) ?? -1);
    }
    for (const { mesh } of this.meshes) {
      for (let i = 0; i < count; i++) mesh.setColorAt(i, this.palette[colors[i]] ?? this.scratchColor.set(1, 1, 1));
      if (mesh.instanceColor) mesh.instanceColor.needsUpdate = true;
      mesh.count = count;
      mesh.geometry = count > this.crowdAbove ? this.assets.crowdGeometry : this.assets.geometry;
    }
    this.dents.reset(count);
    this.foil?.setBodies(colors, models, this.palette);
  }

  /**
   * Writes interpolated poses into the instance matrices, each scaled by its
   * body's size now (`bodyScales`, one per body; 1 where it is short): the
   * pose is the mesh frame's origin, so translate · rotate · scale draws a
   * shrunken balloon where the engine has it. With `now` (ms since the
   * epoch), the dents taken in (`takeDents`) are drawn as they stand then.
   */
  update(
    prev: Float32Array,
    curr: Float32Array,
    count: number,
    alpha: number,
    bodyScales: Float32Array,
    now?: number,
  ): void {
    const n = Math.min(count, this.capacity);
    this.drawnCount = n;
    let lost = 0;
    let latex = 0;
    for (const m of this.meshes) m.drawn.fill(0, 0, n);
    for (let i = 0; i < n; i++) {
      const size = i < bodyScales.length ? bodyScales[i] : 1;
      const mesh = this.meshes[this.bodyMesh[i]];
      if (!mesh) continue; // a foil body, or routed before a new world's bodies came
      mesh.drawn[i] = this.scales[i] * size;
      lost += 1 - size * size * size;
      latex++;
    }
    for (const { mesh, drawn } of this.meshes) {
      writeInstanceMatrices(mesh.instanceMatrix.array as Float32Array, prev, curr, n, alpha, drawn);
      mesh.count = n;
      mesh.instanceMatrix.clearUpdateRanges();
      mesh.instanceMatrix.addUpdateRange(0, n * 16);
      mesh.instanceMatrix.needsUpdate = true;
    }
    if (latex > 0) this.materials.setAge(lost / latex / VOLUME_LOST_WHEN_LANDED);
    if (now !== undefined) {
      this.dents.write(this.squash.array as Float32Array, now);
      this.squash.clearUpdateRanges();
      this.squash.addUpdateRange(0, n * 4);
      this.squash.needsUpdate = true;
    }
    this.foil?.update(prev, curr, alpha, bodyScales, now !== undefined ? (this.squash.array as Float32Array) : undefined);
  }

  /**
   * A frame's dents (`SQUASH_STRIDE` per body, made at `stepTime`, ms since
   * the epoch), taken as each frame arrives: the page may draw less often
   * than frames come.
   */
  takeDents(table: Float32Array, stepTime: number): void {
    this.dents.add(table, stepTime);
  }

  /** Body `i`'s dent `ageMs` after it was made, as it would be drawn then (zeros: round). */
  squashAt(i: number, ageMs: number): [number, number, number, number] {
    return this.dents.at(i, ageMs);
  }

  /** Body `i`'s dent as drawn now: the normal times the depth (m, world) and the reach. */
  squashOf(i: number): [number, number, number, number] {
    const a = this.squash.array as Float32Array;
    return [a[4 * i], a[4 * i + 1], a[4 * i + 2], a[4 * i + 3]];
  }

  /** The finish meshes: each one's finish, material and the bodies it draws (size above 0). */
  finishesDrawn(): { finish: Finish; material: string; iridescence: number; metalness: number; transmission: number; sheen: number; bodies: number }[] {
    return this.meshes.map(({ finish, mesh, drawn }) => {
      const m = mesh.material as THREE.MeshPhysicalMaterial;
      let bodies = 0;
      for (let i = 0; i < mesh.count; i++) if (drawn[i] > 0) bodies++;
      return { finish, material: m.type, iridescence: m.iridescence, metalness: m.metalness, transmission: m.transmission, sheen: m.sheen, bodies };
    });
  }

  /** Bodies the last update drew (latex meshes and foil together). */
  get count(): number {
    return this.drawnCount;
  }

  setVisible(visible: boolean): void {
    this.group.visible = visible;
  }
}
