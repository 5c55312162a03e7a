// Debug view: every balloon's sphere tree (the report's Figure 2), drawn as
// wireframe spheres coloured by depth, the last step's contact points (a dot
// at each and a short segment along its normal: red between balloons, blue
// against the room) and the ribbons' particles (a dot at each), in
// preallocated buffers updated in place.

import * as THREE from "three";
import type { TreeNode } from "../sim/engine";
import { POSE_STRIDE } from "./poseMath";
import { contactArrays, writeContactGeometry, type ContactArrays } from "./contactLines";

/** Most contacts drawn (the worker sends at most this many). */
export const MAX_DRAWN_CONTACTS = 32_768;
/** Length of a contact's normal segment, m (a balloon is about 0.3 m across). */
const NORMAL_LENGTH = 0.06;
/** Size of a contact dot, CSS pixels. */
const POINT_SIZE = 5;
/** Size and colour of a ribbon particle's dot, CSS pixels. */
const RIBBON_POINT_SIZE = 4;
const RIBBON_POINT_COLOR = 0x39ff88;

const DEPTH_COLORS = [0xffe066, 0x4dd2ff, 0x7cff6b, 0xff7ad9, 0xffffff];

export class DebugView {
  readonly group = new THREE.Group();
  private spheres: THREE.InstancedMesh;
  private capacity = 0;
  private trees: TreeNode[][] = [];
  private readonly sphereGeometry = new THREE.IcosahedronGeometry(1, 2);
  private readonly sphereMaterial = new THREE.MeshBasicMaterial({ wireframe: true, transparent: true, opacity: 0.55, depthWrite: false });
  private readonly matrix = new THREE.Matrix4();
  private readonly position = new THREE.Vector3();
  private readonly quaternion = new THREE.Quaternion();
  private readonly scale = new THREE.Vector3();
  private readonly color = new THREE.Color();
  private readonly contactData: ContactArrays = contactArrays(MAX_DRAWN_CONTACTS);
  private readonly contactPoints: THREE.Points;
  private readonly contactLines: THREE.LineSegments;
  private ribbonPoints: THREE.Points<THREE.BufferGeometry, THREE.PointsMaterial>;
  private ribbonCapacity = 0;
  /** Contacts drawn now. */
  contactCount = 0;
  /** Ribbon particles drawn now. */
  ribbonPointCount = 0;

  constructor() {
    this.group.name = "debug";
    this.group.visible = false;
    this.spheres = this.makeSpheres(1024);
    const d = this.contactData;
    const points = new THREE.BufferGeometry();
    points.setAttribute("position", new THREE.BufferAttribute(d.points, 3).setUsage(THREE.DynamicDrawUsage));
    points.setAttribute("color", new THREE.BufferAttribute(d.pointColors, 3).setUsage(THREE.DynamicDrawUsage));
    points.setDrawRange(0, 0);
    // Drawn over everything: contacts hide inside the spheres otherwise.
    const onTop = { depthTest: false, depthWrite: false, transparent: true, vertexColors: true };
    this.contactPoints = new THREE.Points(points, new THREE.PointsMaterial({ ...onTop, size: POINT_SIZE, sizeAttenuation: false }));
    const lines = new THREE.BufferGeometry();
    lines.setAttribute("position", new THREE.BufferAttribute(d.lines, 3).setUsage(THREE.DynamicDrawUsage));
    lines.setAttribute("color", new THREE.BufferAttribute(d.lineColors, 3).setUsage(THREE.DynamicDrawUsage));
    lines.setDrawRange(0, 0);
    this.contactLines = new THREE.LineSegments(lines, new THREE.LineBasicMaterial(onTop));
    this.ribbonPoints = new THREE.Points(
      new THREE.BufferGeometry(),
      new THREE.PointsMaterial({ color: RIBBON_POINT_COLOR, size: RIBBON_POINT_SIZE, sizeAttenuation: false, depthTest: false, depthWrite: false, transparent: true }),
    );
    this.growRibbonPoints(1024);
    for (const o of [this.contactPoints, this.contactLines, this.ribbonPoints]) {
      o.frustumCulled = false;
      o.renderOrder = 10;
      this.group.add(o);
    }
  }

  /** Shows `count` contacts of `contacts` (sim/frameLayout.ts layout): call when a new frame arrives. */
  setContacts(contacts: Float32Array, count: number): void {
    const n = writeContactGeometry(contacts, count, this.contactData, NORMAL_LENGTH);
    this.contactCount = n;
    for (const [object, vertices] of [
      [this.contactPoints, n],
      [this.contactLines, 2 * n],
    ] as const) {
      const g = object.geometry;
      g.setDrawRange(0, vertices);
      for (const name of ["position", "color"]) {
        const a = g.getAttribute(name) as THREE.BufferAttribute;
        a.clearUpdateRanges();
        a.addUpdateRange(0, vertices * 3);
        a.needsUpdate = true;
      }
    }
  }

  private growRibbonPoints(capacity: number): void {
    const attribute = new THREE.BufferAttribute(new Float32Array(capacity * 3), 3).setUsage(THREE.DynamicDrawUsage);
    this.ribbonPoints.geometry.setAttribute("position", attribute);
    this.ribbonCapacity = capacity;
  }

  /** Shows a dot at each ribbon particle of `points` (x, y, z each). */
  setRibbonPoints(points: Float32Array): void {
    const n = Math.floor(points.length / 3);
    if (n > this.ribbonCapacity) this.growRibbonPoints(Math.max(n, this.ribbonCapacity * 2));
    const attribute = this.ribbonPoints.geometry.getAttribute("position") as THREE.BufferAttribute;
    (attribute.array as Float32Array).set(points.subarray(0, n * 3));
    attribute.clearUpdateRanges();
    attribute.addUpdateRange(0, n * 3);
    attribute.needsUpdate = true;
    this.ribbonPoints.geometry.setDrawRange(0, n);
    this.ribbonPointCount = n;
  }

  private makeSpheres(capacity: number): THREE.InstancedMesh {
    if (this.spheres) {
      this.group.remove(this.spheres);
      this.spheres.dispose();
    }
    const mesh = new THREE.InstancedMesh(this.sphereGeometry, this.sphereMaterial, capacity);
    mesh.frustumCulled = false;
    mesh.count = 0;
    mesh.setColorAt(0, this.color.set(1, 1, 1));
    this.capacity = capacity;
    this.spheres = mesh;
    this.group.add(mesh);
    return mesh;
  }

  setTrees(trees: TreeNode[][]): void {
    this.trees = trees;
  }

  get visible(): boolean {
    return this.group.visible;
  }

  set visible(on: boolean) {
    this.group.visible = on;
  }

  /**
   * Places every node of every balloon's tree (current poses, no
   * interpolation: it is a debug view), each tree at its body's size now
   * (`scales`, 1 where short), as the engine collides with it.
   */
  update(poses: Float32Array, offset: number, count: number, models: Uint32Array | null, scales: Float32Array | null = null): void {
    if (!this.group.visible) return;
    let needed = 0;
    for (let i = 0; i < count; i++) needed += this.trees[models ? models[i] : 0]?.length ?? 0;
    if (needed > this.capacity) this.makeSpheres(Math.max(needed, this.capacity * 2));
    let k = 0;
    for (let i = 0; i < count; i++) {
      const tree = this.trees[models ? models[i] : 0];
      if (!tree) continue;
      const o = offset + i * POSE_STRIDE;
      const s = scales && i < scales.length ? scales[i] : 1;
      this.quaternion.set(poses[o + 3], poses[o + 4], poses[o + 5], poses[o + 6]);
      for (const node of tree) {
        this.position.set(node.center[0] * s, node.center[1] * s, node.center[2] * s).applyQuaternion(this.quaternion);
        this.position.x += poses[o];
        this.position.y += poses[o + 1];
        this.position.z += poses[o + 2];
        this.scale.setScalar(node.radius * s);
        this.matrix.compose(this.position, this.quaternion, this.scale);
        this.spheres.setMatrixAt(k, this.matrix);
        this.spheres.setColorAt(k, this.color.setHex(DEPTH_COLORS[Math.min(node.depth, DEPTH_COLORS.length - 1)]));
        k++;
      }
    }
    this.spheres.count = k;
    this.spheres.instanceMatrix.needsUpdate = true;
    if (this.spheres.instanceColor) this.spheres.instanceColor.needsUpdate = true;
  }
}
