// The selected balloon's outline: the balloon's own surface, a few per cent
// larger about its centre, drawn from its back faces in one flat colour. The
// balloon hides the shell's middle and the rim shows around it: one extra
// draw call for one balloon, no post-processing pass.

import * as THREE from "three";
import { POSE_STRIDE, writeInstanceMatrices } from "./poseMath";
import type { ModelMesh, TreeNode } from "../sim/engine";

/** How much larger the shell is than the balloon. */
export const OUTLINE_GROWTH = 1.12;
export const OUTLINE_COLOR = "#ffffff";

/** What the outline needs of a world: each model's shape and size. */
export interface OutlineModels {
  /** The latex balloon's mesh (the OBJ), and its diameter, m. */
  latex: THREE.BufferGeometry;
  latexDiameter: number;
  /** Each model's diameter, m. */
  diameters: number[];
  /** Each foil model's surface; null for latex. */
  foilMeshes: (ModelMesh | null)[];
  trees: TreeNode[][];
}

/**
 * The shell's matrix (column-major, 16 floats into `out`) from the balloon's
 * drawn matrix `drawn` (pose · its uniform scale `scale`): grown by
 * `growth` about `center`, the root sphere's centre in the body frame at the
 * drawn size.
 */
export function outlineMatrix(out: THREE.Matrix4, drawn: THREE.Matrix4, center: THREE.Vector3, scale: number, growth = OUTLINE_GROWTH): THREE.Matrix4 {
  // In the mesh's own units the centre is at center / scale.
  const c = center.clone().divideScalar(scale || 1);
  const about = new THREE.Matrix4().makeTranslation(c.x, c.y, c.z);
  about.multiply(new THREE.Matrix4().makeScale(growth, growth, growth));
  about.multiply(new THREE.Matrix4().makeTranslation(-c.x, -c.y, -c.z));
  return out.multiplyMatrices(drawn, about);
}

export class SelectionOutline {
  readonly mesh: THREE.Mesh;
  private models: OutlineModels | null = null;
  private readonly foilGeometries = new Map<number, THREE.BufferGeometry>();
  private readonly matrixArray = new Float32Array(16);
  private readonly drawn = new THREE.Matrix4();
  private readonly center = new THREE.Vector3();
  private readonly scaleArray = new Float32Array(1);

  constructor() {
    const material = new THREE.MeshBasicMaterial({ color: OUTLINE_COLOR, side: THREE.BackSide, toneMapped: false });
    this.mesh = new THREE.Mesh(new THREE.BufferGeometry(), material);
    this.mesh.name = "selection-outline";
    this.mesh.matrixAutoUpdate = false;
    this.mesh.frustumCulled = false;
    this.mesh.visible = false;
  }

  setWorld(models: OutlineModels): void {
    this.models = models;
    for (const g of this.foilGeometries.values()) g.dispose();
    this.foilGeometries.clear();
    this.mesh.visible = false;
  }

  private geometry(model: number): THREE.BufferGeometry | null {
    const models = this.models;
    if (!models) return null;
    const foil = models.foilMeshes[model];
    if (!foil) return models.latex;
    let g = this.foilGeometries.get(model);
    if (!g) {
      g = new THREE.BufferGeometry();
      g.setAttribute("position", new THREE.BufferAttribute(foil.positions, 3));
      g.setIndex(new THREE.BufferAttribute(foil.indices, 1));
      this.foilGeometries.set(model, g);
    }
    return g;
  }

  /**
   * Outlines body `index` (-1: none) of the frame, its pose interpolated as the
   * balloons are (`alpha` between `prev` and `curr`), at its size now (`bodyScale`).
   */
  update(index: number, model: number, prev: Float32Array, curr: Float32Array, alpha: number, bodyScale: number): void {
    const models = this.models;
    const geometry = index >= 0 ? this.geometry(model) : null;
    const o = index * POSE_STRIDE;
    if (!models || !geometry || curr.length < o + POSE_STRIDE) {
      this.mesh.visible = false;
      return;
    }
    const foil = !!models.foilMeshes[model];
    const modelScale = foil ? 1 : (models.diameters[model] ?? models.latexDiameter) / models.latexDiameter;
    const scale = modelScale * bodyScale;
    this.scaleArray[0] = scale;
    const p = prev.length >= o + POSE_STRIDE ? prev.subarray(o, o + POSE_STRIDE) : curr.subarray(o, o + POSE_STRIDE);
    writeInstanceMatrices(this.matrixArray, p, curr.subarray(o, o + POSE_STRIDE), 1, alpha, this.scaleArray);
    this.drawn.fromArray(this.matrixArray);
    const root = models.trees[model]?.[0];
    this.center.set(...(root?.center ?? [0, 0, 0])).multiplyScalar(bodyScale);
    outlineMatrix(this.mesh.matrix, this.drawn, this.center, scale);
    this.mesh.matrixWorldNeedsUpdate = true;
    this.mesh.geometry = geometry;
    this.mesh.visible = true;
  }
}
