// Force arrows: each force the engine recorded on a balloon over the last
// step, drawn from where it acts (weight at the centre of mass, buoyancy at the
// centre of buoyancy, the ribbon's pull at the knot), every arrow to one
// length scale. All arrows share two InstancedMeshes (shafts and heads, each
// instance tinted by its kind): two draw calls however many balloons.

import * as THREE from "three";
import { FORCE_KINDS, forceRowCount, readForceRow, type ForceKind, type ForceRow, type Vec3 } from "../sim/forcesFrame";

/**
 * Newtons per metre of arrow: a latex balloon's weight (≈ 0.05 N) is a
 * 20 cm arrow and its buoyancy (≈ 0.13 N) half a metre, beside a 28 cm balloon.
 */
export const NEWTONS_PER_METRE = 0.25;
/** Longest arrow drawn, m: an impact's contact force is cut here (its value is on the card). */
export const MAX_ARROW_M = 1.5;
/** Shorter arrows are not drawn, m (a force of a thousandth of a newton). */
export const MIN_ARROW_M = 0.004;
/** Sideways shift of the kinds that often lie along another (drag along weight), m. */
const SIDE_SHIFT_M: Record<ForceKind, number> = { weight: 0, buoyancy: 0, drag: 0.035, contact: -0.035, ribbon: 0, other: 0.07 };

/** Each kind's colour, and its name in the legend. */
export const FORCE_STYLE: Record<ForceKind, { color: string; label: string }> = {
  weight: { color: "#ff4b3e", label: "weight" },
  buoyancy: { color: "#27d9ff", label: "buoyancy" },
  drag: { color: "#ffd21f", label: "air drag" },
  contact: { color: "#ff5ce1", label: "contact" },
  ribbon: { color: "#f4f4f4", label: "ribbon's pull" },
  other: { color: "#9dff4a", label: "hand, fields" },
};

/** One arrow: a force and where it is drawn. */
export interface Arrow {
  kind: ForceKind;
  /** Dense index of the balloon it acts on. */
  body: number;
  /** Where the force acts, m. */
  origin: Vec3;
  /** The force, N (the engine's). */
  force: Vec3;
  /** Unit direction of the force. */
  direction: Vec3;
  /** Length drawn, m: |force| / `NEWTONS_PER_METRE`, at most `MAX_ARROW_M`. */
  length: number;
  /** Whether the arrow was cut at `MAX_ARROW_M`. */
  clipped: boolean;
}

/** Where a force of `kind` acts on the balloon of `row`; null when it has no such point (no ribbon). */
export function pointOfAction(row: ForceRow, kind: ForceKind): Vec3 | null {
  switch (kind) {
    case "weight":
    case "contact":
    case "other":
      return row.centerOfMass;
    case "buoyancy":
    case "drag":
      // Drag acts on the envelope's outline, whose centre is the displaced air's.
      return row.centerOfBuoyancy;
    case "ribbon":
      return row.knot;
  }
}

/** The arrows of one balloon's row, longer than `MIN_ARROW_M`, in `FORCE_KINDS` order. */
export function arrowsOfRow(row: ForceRow, newtonsPerMetre = NEWTONS_PER_METRE, maxLength = MAX_ARROW_M): Arrow[] {
  const arrows: Arrow[] = [];
  for (const kind of FORCE_KINDS) {
    const force = row.forces[kind];
    const magnitude = Math.hypot(force[0], force[1], force[2]);
    const origin = pointOfAction(row, kind);
    const full = magnitude / newtonsPerMetre;
    if (!origin || !(full >= MIN_ARROW_M) || !Number.isFinite(full)) continue;
    const direction: Vec3 = [force[0] / magnitude, force[1] / magnitude, force[2] / magnitude];
    arrows.push({ kind, body: row.index, origin, force, direction, length: Math.min(full, maxLength), clipped: full > maxLength });
  }
  return arrows;
}

/** Every arrow of `rows` (the frame's force rows), or of body `only`'s row alone when it is 0 or more. */
export function arrowsOfRows(rows: ArrayLike<number>, only = -1): Arrow[] {
  const arrows: Arrow[] = [];
  const n = forceRowCount(rows);
  for (let i = 0; i < n; i++) {
    const row = readForceRow(rows, i);
    if (only >= 0 && row.index !== only) continue;
    arrows.push(...arrowsOfRow(row));
  }
  return arrows;
}

/**
 * Where an arrow's tail is drawn: at its point of action, shifted sideways (as
 * seen along `view`, the camera's direction) by its kind's shift, so that
 * drag and contact do not hide under weight and buoyancy.
 */
export function arrowTail(arrow: Arrow, view: Vec3): Vec3 {
  const shift = SIDE_SHIFT_M[arrow.kind];
  const [dx, dy, dz] = arrow.direction;
  // Sideways: perpendicular to the arrow and to the line of sight.
  let sx = dy * view[2] - dz * view[1];
  let sy = dz * view[0] - dx * view[2];
  let sz = dx * view[1] - dy * view[0];
  const len = Math.hypot(sx, sy, sz);
  if (shift === 0 || len < 1e-6) return [...arrow.origin];
  sx /= len;
  sy /= len;
  sz /= len;
  return [arrow.origin[0] + sx * shift, arrow.origin[1] + sy * shift, arrow.origin[2] + sz * shift];
}

/** Shaft radius and head size, m: thin beside a balloon, the head short on a short arrow. */
const SHAFT_RADIUS = 0.008;
const HEAD_RADIUS = 0.024;
const HEAD_LENGTH = 0.07;

/** The arrows in the scene. */
export class ForceArrows {
  readonly group = new THREE.Group();
  /** The arrows drawn now (for the test hook and the legend). */
  arrows: Arrow[] = [];
  private shafts: THREE.InstancedMesh;
  private heads: THREE.InstancedMesh;
  private capacity = 0;
  private readonly shaftGeometry: THREE.BufferGeometry;
  private readonly headGeometry: THREE.BufferGeometry;
  private readonly material: THREE.MeshBasicMaterial;
  private readonly colors = new Map<ForceKind, THREE.Color>(FORCE_KINDS.map((k) => [k, new THREE.Color(FORCE_STYLE[k].color)]));
  private readonly m = new THREE.Matrix4();
  private readonly q = new THREE.Quaternion();
  private readonly up = new THREE.Vector3(0, 1, 0);
  private readonly dir = new THREE.Vector3();
  private readonly pos = new THREE.Vector3();
  private readonly scale = new THREE.Vector3();

  constructor() {
    this.group.name = "force-arrows";
    // Unit shapes standing on the origin along +y, stretched per instance.
    this.shaftGeometry = new THREE.CylinderGeometry(1, 1, 1, 8, 1).translate(0, 0.5, 0);
    this.headGeometry = new THREE.ConeGeometry(1, 1, 12, 1).translate(0, 0.5, 0);
    // Drawn over everything, unlit: an arrow is a diagram, and starts inside its balloon.
    this.material = new THREE.MeshBasicMaterial({ color: 0xffffff, depthTest: false, depthWrite: false, toneMapped: false });
    this.shafts = this.makeMesh(this.shaftGeometry, "force-arrow-shafts", 16);
    this.heads = this.makeMesh(this.headGeometry, "force-arrow-heads", 16);
    this.capacity = 16;
  }

  private makeMesh(geometry: THREE.BufferGeometry, name: string, capacity: number): THREE.InstancedMesh {
    const mesh = new THREE.InstancedMesh(geometry, this.material, capacity);
    mesh.name = name;
    mesh.instanceMatrix.setUsage(THREE.DynamicDrawUsage);
    mesh.frustumCulled = false;
    mesh.renderOrder = 10;
    mesh.count = 0;
    mesh.setColorAt(0, new THREE.Color(1, 1, 1));
    this.group.add(mesh);
    return mesh;
  }

  private grow(count: number): void {
    if (count <= this.capacity) return;
    const capacity = Math.max(count, this.capacity * 2);
    for (const mesh of [this.shafts, this.heads]) {
      this.group.remove(mesh);
      mesh.dispose();
    }
    this.shafts = this.makeMesh(this.shaftGeometry, "force-arrow-shafts", capacity);
    this.heads = this.makeMesh(this.headGeometry, "force-arrow-heads", capacity);
    this.capacity = capacity;
  }

  /** Draws `arrows`, their tails shifted sideways as seen along `view` (the camera's unit direction). */
  set(arrows: Arrow[], view: Vec3): void {
    this.arrows = arrows;
    this.grow(arrows.length);
    arrows.forEach((a, i) => {
      const head = Math.min(HEAD_LENGTH, a.length * 0.5);
      const tail = arrowTail(a, view);
      this.dir.set(...a.direction);
      this.q.setFromUnitVectors(this.up, this.dir);
      this.pos.set(...tail);
      this.m.compose(this.pos, this.q, this.scale.set(SHAFT_RADIUS, a.length - head, SHAFT_RADIUS));
      this.shafts.setMatrixAt(i, this.m);
      this.pos.addScaledVector(this.dir, a.length - head);
      const r = Math.min(HEAD_RADIUS, head * 0.6);
      this.m.compose(this.pos, this.q, this.scale.set(r, head, r));
      this.heads.setMatrixAt(i, this.m);
      const color = this.colors.get(a.kind)!;
      this.shafts.setColorAt(i, color);
      this.heads.setColorAt(i, color);
    });
    for (const mesh of [this.shafts, this.heads]) {
      mesh.count = arrows.length;
      mesh.instanceMatrix.needsUpdate = true;
      if (mesh.instanceColor) mesh.instanceColor.needsUpdate = true;
    }
  }

  clear(): void {
    this.set([], [0, 0, -1]);
  }
}
