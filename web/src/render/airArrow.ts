// The air's velocity at the selected balloon, drawn as one arrow from its
// centre of mass (beside the force arrows, which are newtons; this one is
// metres per second, `METRES_PER_M_S` of arrow each). The engine gives the
// velocity (the card's `air_velocity_m_s`); the balloon's drag acts against
// the air's velocity relative to its own, and is the force arrows' "air drag".

import * as THREE from "three";
import type { Vec3 } from "../sim/airLayout";

/** Metres of arrow per m/s of air. */
export const METRES_PER_M_S = 0.3;
/** Longest arrow drawn, m, and the slowest air drawn, m/s. */
export const MAX_AIR_ARROW_M = 1.5;
export const MIN_AIR_SPEED = 0.02;
export const AIR_ARROW_COLOR = "#8fd3ff";

/** The arrow for air velocity `u` (m/s): its unit direction and length (m), or null when the air is still there. */
export function airArrow(u: Vec3): { direction: Vec3; length: number } | null {
  const speed = Math.hypot(u[0], u[1], u[2]);
  if (!(speed >= MIN_AIR_SPEED)) return null;
  return { direction: [u[0] / speed, u[1] / speed, u[2] / speed], length: Math.min(MAX_AIR_ARROW_M, speed * METRES_PER_M_S) };
}

export class AirArrow {
  readonly arrow = new THREE.ArrowHelper(new THREE.Vector3(0, 1, 0), new THREE.Vector3(), 1, AIR_ARROW_COLOR, 0.08, 0.04);
  private readonly origin = new THREE.Vector3();
  private readonly direction = new THREE.Vector3();

  constructor() {
    this.arrow.name = "air-arrow";
    this.arrow.visible = false;
    // A diagram over the scene, as the force arrows are.
    this.arrow.traverse((o) => {
      const material = (o as THREE.Mesh).material as THREE.Material | undefined;
      if (material) {
        material.depthTest = false;
        material.depthWrite = false;
        material.toneMapped = false;
      }
      o.renderOrder = 11;
    });
  }

  /** The air `u` (m/s) at `at` (m); null for either hides the arrow. */
  set(at: Vec3 | null, u: Vec3 | null): void {
    const a = at && u ? airArrow(u) : null;
    this.arrow.visible = !!a;
    if (!a || !at) return;
    this.arrow.position.copy(this.origin.set(...at));
    this.arrow.setDirection(this.direction.set(...a.direction));
    this.arrow.setLength(a.length, Math.min(0.08, a.length * 0.4), Math.min(0.04, a.length * 0.2));
  }
}
