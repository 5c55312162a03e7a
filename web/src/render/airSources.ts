// The fans and vents in the room, drawn from the engine's source rows every
// frame: each part is one InstancedMesh shared by every fan (base, pole,
// motor, blades, guard) or vent (frame, grille), so the room's fans cost
// seven draw calls however many there are. A fan's head is turned to where
// it blows now, so a sweeping fan swings; its blades turn at a rate from its
// outlet speed (fanGeometry.ts). A fan being placed is drawn too, tinted.

import * as THREE from "three";
import { mergeGeometries } from "three/examples/jsm/utils/BufferGeometryUtils.js";
import type { AirSource, Vec3 } from "../sim/airLayout";
import { bladeTurnRate, fanPose, rotate } from "./fanGeometry";

/** The placed fan's tint while it is being aimed. */
const PREVIEW_TINT = new THREE.Color(0.55, 0.85, 1.0);
/** The selected fan's tint. */
const SELECTED_TINT = new THREE.Color(1.0, 0.85, 0.45);
const PLAIN = new THREE.Color(1, 1, 1);

/** Three blades in the z = 0 plane round the z axis, for an outlet of diameter 1. */
function bladeGeometry(): THREE.BufferGeometry {
  const blades: THREE.BufferGeometry[] = [];
  for (let k = 0; k < 3; k++) {
    // A flattened disc as a blade, from near the hub to near the guard, pitched a little.
    const blade = new THREE.SphereGeometry(1, 12, 6);
    blade.scale(0.2, 0.1, 0.012);
    blade.rotateX(0.35);
    blade.translate(0.25, 0, 0);
    blade.rotateZ((k * 2 * Math.PI) / 3);
    blades.push(blade.toNonIndexed());
  }
  const hub = new THREE.CylinderGeometry(0.07, 0.07, 0.05, 16).rotateX(Math.PI / 2).toNonIndexed();
  return mergeGeometries([...blades, hub]);
}

/** A guard ring of diameter 1 in the z = 0 plane, with four spokes across. */
function guardGeometry(): THREE.BufferGeometry {
  const ring = new THREE.TorusGeometry(0.5, 0.012, 6, 40).toNonIndexed();
  const spokes = [0, Math.PI / 2].map((a) => new THREE.CylinderGeometry(0.006, 0.006, 1, 5).rotateZ(a).translate(0, 0, 0.03).toNonIndexed());
  return mergeGeometries([ring, ...spokes]);
}

/** A vent's square frame (side 1, z = 0 plane) and its grille of slats, facing +z. */
function ventGeometries(): { frame: THREE.BufferGeometry; grille: THREE.BufferGeometry } {
  const sides = [
    new THREE.BoxGeometry(1, 0.08, 0.04).translate(0, 0.46, 0),
    new THREE.BoxGeometry(1, 0.08, 0.04).translate(0, -0.46, 0),
    new THREE.BoxGeometry(0.08, 0.84, 0.04).translate(0.46, 0, 0),
    new THREE.BoxGeometry(0.08, 0.84, 0.04).translate(-0.46, 0, 0),
  ].map((g) => g.toNonIndexed());
  const slats: THREE.BufferGeometry[] = [];
  for (let k = -3; k <= 3; k++) slats.push(new THREE.BoxGeometry(0.84, 0.03, 0.02).rotateX(0.6).translate(0, k * 0.11, 0.01).toNonIndexed());
  return { frame: mergeGeometries(sides), grille: mergeGeometries(slats) };
}

/** The fans and vents of the room. */
export class AirSourcesView {
  readonly group = new THREE.Group();
  /** Fans and vents drawn now (the test hook reads them). */
  fans = 0;
  vents = 0;
  /** Each drawn fan's blade angle, rad, by its jet index. */
  private readonly bladeAngle: number[] = [];
  private readonly meshes: Record<"base" | "pole" | "motor" | "blades" | "guard" | "ventFrame" | "ventGrille", THREE.InstancedMesh>;
  private floorY = 0;
  private readonly m = new THREE.Matrix4();
  private readonly q = new THREE.Quaternion();
  private readonly spin = new THREE.Quaternion();
  private readonly turned = new THREE.Quaternion();
  private readonly p = new THREE.Vector3();
  private readonly s = new THREE.Vector3();
  private readonly zAxis = new THREE.Vector3(0, 0, 1);

  constructor(readonly capacity: number) {
    this.group.name = "air-sources";
    const metal = new THREE.MeshStandardMaterial({ color: 0xd9dde2, metalness: 0.6, roughness: 0.35 });
    const dark = new THREE.MeshStandardMaterial({ color: 0x3a3f46, metalness: 0.3, roughness: 0.5 });
    const blade = new THREE.MeshStandardMaterial({ color: 0xe8f1fb, roughness: 0.4, transparent: true, opacity: 0.85, side: THREE.DoubleSide });
    const white = new THREE.MeshStandardMaterial({ color: 0xf4f4f2, roughness: 0.6 });
    const vent = ventGeometries();
    // One more instance than sources: the fan being placed.
    const n = capacity + 1;
    const make = (name: string, geometry: THREE.BufferGeometry, material: THREE.Material) => {
      const mesh = new THREE.InstancedMesh(geometry, material, n);
      mesh.name = name;
      mesh.count = 0;
      mesh.frustumCulled = false;
      mesh.instanceMatrix.setUsage(THREE.DynamicDrawUsage);
      mesh.setColorAt(0, PLAIN);
      this.group.add(mesh);
      return mesh;
    };
    this.meshes = {
      base: make("fan-bases", new THREE.CylinderGeometry(0.16, 0.19, 0.03, 24).translate(0, 0.015, 0), dark),
      pole: make("fan-poles", new THREE.CylinderGeometry(0.014, 0.014, 1, 8).translate(0, 0.5, 0), metal),
      motor: make("fan-motors", new THREE.CylinderGeometry(0.06, 0.075, 0.14, 16).rotateX(Math.PI / 2), dark),
      blades: make("fan-blades", bladeGeometry(), blade),
      guard: make("fan-guards", guardGeometry(), metal),
      ventFrame: make("vent-frames", vent.frame, white),
      ventGrille: make("vent-grilles", vent.grille, dark),
    };
  }

  /** The floor the fans stand on, m. */
  setFloor(y: number): void {
    this.floorY = y;
  }

  private place(mesh: THREE.InstancedMesh, i: number, position: Vec3, rotation: THREE.Quaternion, scale: Vec3, tint: THREE.Color): void {
    this.m.compose(this.p.set(...position), rotation, this.s.set(...scale));
    mesh.setMatrixAt(i, this.m);
    mesh.setColorAt(i, tint);
  }

  /** One fan at instance `i`; `angle` its blades' turn, rad. */
  private drawFan(i: number, outlet: Vec3, aim: Vec3, diameter: number, angle: number, tint: THREE.Color): void {
    const pose = fanPose(outlet, aim, diameter, this.floorY);
    const { base, pole, motor, blades, guard } = this.meshes;
    this.q.identity();
    this.place(base, i, pose.base, this.q, [1, 1, 1], tint);
    this.place(pole, i, pose.pole.bottom, this.q, [1, Math.max(pose.pole.length, 1e-3), 1], tint);
    const [x, y, z, w] = pose.head.rotation;
    this.q.set(x, y, z, w);
    const d = diameter;
    this.place(motor, i, pose.head.motor, this.q, [d / 0.4, d / 0.4, d / 0.4], tint);
    this.place(guard, i, pose.head.outlet, this.q, [d, d, d], tint);
    this.spin.setFromAxisAngle(this.zAxis, angle);
    const turned = this.turned.copy(this.q).multiply(this.spin);
    // Blades a little behind the guard's front spokes.
    const back = rotate(pose.head.rotation, [0, 0, -0.02 * d]);
    const at: Vec3 = [outlet[0] + back[0], outlet[1] + back[1], outlet[2] + back[2]];
    this.place(blades, i, at, turned, [d, d, d], tint);
  }

  /**
   * Draws `sources` now, after `dt` seconds of turning (0 while paused);
   * `preview`: a fan being placed; `selected`: the jet index of the fan the
   * panel's speed is for (-1: none).
   */
  update(sources: readonly AirSource[], dt: number, preview: { outlet: Vec3; aim: Vec3; diameter: number } | null, selected = -1): void {
    let fans = 0;
    let vents = 0;
    for (const s of sources) {
      if (s.kind === "fan" && fans < this.capacity) {
        const angle = (this.bladeAngle[s.jet] ?? 0) + dt * bladeTurnRate(s.speed, s.diameter);
        this.bladeAngle[s.jet] = angle % (2 * Math.PI);
        this.drawFan(fans++, s.outlet, s.aim, s.diameter, angle, s.jet === selected ? SELECTED_TINT : PLAIN);
      } else if (s.kind === "vent" && vents < this.capacity) {
        const [x, y, z, w] = fanPose(s.outlet, s.aim, s.diameter, this.floorY).head.rotation;
        this.q.set(x, y, z, w);
        const side = 1.3 * s.diameter;
        this.place(this.meshes.ventFrame, vents, s.outlet, this.q, [side, side, side], PLAIN);
        this.place(this.meshes.ventGrille, vents, s.outlet, this.q, [side, side, side], PLAIN);
        vents++;
      }
    }
    this.bladeAngle.length = Math.min(this.bladeAngle.length, sources.length);
    this.fans = fans;
    this.vents = vents;
    if (preview) this.drawFan(fans++, preview.outlet, preview.aim, preview.diameter, 0, PREVIEW_TINT);
    const { base, pole, motor, blades, guard, ventFrame, ventGrille } = this.meshes;
    for (const mesh of [base, pole, motor, blades, guard]) this.commit(mesh, fans);
    for (const mesh of [ventFrame, ventGrille]) this.commit(mesh, vents);
  }

  private commit(mesh: THREE.InstancedMesh, count: number): void {
    // A room without fans (or vents) uploads nothing.
    if (count === 0 && mesh.count === 0) return;
    mesh.count = count;
    mesh.instanceMatrix.needsUpdate = true;
    if (mesh.instanceColor) mesh.instanceColor.needsUpdate = true;
  }

  /** Draw calls the fans and vents take now (an empty part is skipped). */
  drawCalls(): number {
    return Object.values(this.meshes).filter((m) => m.count > 0).length;
  }
}
