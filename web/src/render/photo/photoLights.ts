// The photo's light: what the live view fakes with a shadow-mapped key light,
// a hemisphere light and an environment map, the path tracer gets as light it
// can trace: a large area light above the room standing for the ceiling lamps
// (soft shadows, from its size), a sky of graded light (the environment:
// warm above, dim below) and the live view's fill lamp. The room's faces are
// one-sided (normals inward), and the tracer lets light from outside through
// their backs as the live view's lights do, so the lamp above the ceiling
// lights the room.

import * as THREE from "three";
import { GradientEquirectTexture } from "three-gpu-pathtracer";

/** The room the lights are fitted to: half-sizes and height of its highest point, m. */
export interface RoomBox {
  halfWidth: number;
  halfDepth: number;
  top: number;
}

/** Area light's radiance per m² of a 6 m room's lamp (chosen by eye against the live view's brightness). */
const LAMP_INTENSITY = 9;
/** Sky (environment) strength, as the live view's environment intensity. */
const SKY_INTENSITY = 0.55;

/** Adds the photo's lights to `scene`; returns what to dispose with it. */
export function addPhotoLights(scene: THREE.Scene, room: RoomBox, liveBackground: THREE.Color | null): { dispose(): void } {
  const lamp = new THREE.RectAreaLight(0xfff1dc, LAMP_INTENSITY, room.halfWidth * 1.2, room.halfDepth * 1.2);
  lamp.position.set(room.halfWidth * 0.3, room.top + 1.5, room.halfDepth * 0.45);
  lamp.lookAt(room.halfWidth * 0.3, 0, room.halfDepth * 0.45);
  scene.add(lamp);

  const sky = new GradientEquirectTexture(64);
  sky.topColor.set(0xfff6e8);
  sky.bottomColor.set(0x40362c);
  sky.exponent = 2;
  sky.update();
  scene.environment = sky;
  scene.environmentIntensity = SKY_INTENSITY;
  scene.background = liveBackground ? liveBackground.clone() : new THREE.Color(0x1d2230);

  const fill = new THREE.PointLight(0xffe2c0, 2 * Math.max(1, (room.halfWidth * room.halfDepth) / 9), 0, 1.6);
  fill.position.set(-room.halfWidth * 0.4, room.top * 0.8, -room.halfDepth * 0.3);
  scene.add(fill);
  return { dispose: () => sky.dispose() };
}
