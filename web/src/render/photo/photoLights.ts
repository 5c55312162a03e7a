// The photo's light: what the live view fakes with a shadow-mapped key light,
// a hemisphere light and an environment map, the path tracer gets as light it
// can trace: a large area light above the room standing for the ceiling lamps
// (soft shadows, from its size), a sky graded between the hemisphere light's
// colours (the environment: warm above, dim below) and the live view's fill
// lamp. Colours, strengths and places are the room's (../roomLights.ts), the
// same the live view reads. The room's faces are one-sided (normals inward),
// and the tracer lets light from outside through their backs as the live
// view's lights do, so the lamp above the ceiling lights the room.

import * as THREE from "three";
import { GradientEquirectTexture } from "three-gpu-pathtracer";
import { AREA_LAMP_INTENSITY, areaLamp, BACKGROUND_COLOR, ENVIRONMENT_INTENSITY, LAMP_COLOR, placeFillLamp, SKY, type RoomBox } from "../roomLights";

export type { RoomBox } from "../roomLights";

/** Adds the photo's lights to `scene`; returns what to dispose with it. */
export function addPhotoLights(scene: THREE.Scene, room: RoomBox, liveBackground: THREE.Color | null): { dispose(): void } {
  const rect = areaLamp(room);
  const lamp = new THREE.RectAreaLight(LAMP_COLOR, AREA_LAMP_INTENSITY, rect.width, rect.depth);
  lamp.position.copy(rect.position);
  lamp.lookAt(rect.position.x, 0, rect.position.z);
  scene.add(lamp);

  const sky = new GradientEquirectTexture(64);
  sky.topColor.set(SKY.above);
  sky.bottomColor.set(SKY.below);
  sky.exponent = 2;
  sky.update();
  scene.environment = sky;
  scene.environmentIntensity = ENVIRONMENT_INTENSITY;
  scene.background = liveBackground ? liveBackground.clone() : new THREE.Color(BACKGROUND_COLOR);

  const fill = new THREE.PointLight();
  placeFillLamp(fill, room);
  scene.add(fill);
  return { dispose: () => sky.dispose() };
}
