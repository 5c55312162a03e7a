// The room's lights, defined once for both ways the page draws the room: the
// live view (a shadow-mapped key light standing for the ceiling lamps, a
// hemisphere light and an environment map: stage.ts) and the photo (the path
// tracer's area lamp, graded sky and the same fill lamp: photo/photoLights.ts).
// Colours, intensities and placements live here, so a change to the room's
// lighting shows in both.

import * as THREE from "three";

/** The room the lights are fitted to: half-sizes and the height of its highest point, m. */
export interface RoomBox {
  halfWidth: number;
  halfDepth: number;
  top: number;
}

/** Behind the room (the page's own background in style.css is the same). */
export const BACKGROUND_COLOR = 0x1d2230;

/** Light that is not the lamps, from above and below: the live hemisphere light's sky and ground, the photo's graded sky. */
export const SKY = { above: 0xfff6e8, below: 0x40362c } as const;
/** The live view's hemisphere light. */
export const HEMISPHERE_INTENSITY = 0.6;
/** The environment's strength: the live view's environment map, the photo's sky. */
export const ENVIRONMENT_INTENSITY = 0.55;

/** The ceiling lamps' colour: the live key light's and the photo's area lamp's. */
export const LAMP_COLOR = 0xfff1dc;
/** The live key light (a directional light). */
export const KEY_INTENSITY = 2.2;
/** The photo's area lamp, radiance per m² (chosen by eye against the live view's brightness). */
export const AREA_LAMP_INTENSITY = 9;

/** Where the live key light shines from (toward the room's centre on the floor). */
export function keyLightPosition(room: RoomBox): THREE.Vector3 {
  return new THREE.Vector3(room.halfWidth * 0.6, room.top * 2.2, room.halfDepth * 0.9);
}

/** The photo's area lamp: a rectangle above the ceiling, facing down (its size gives the soft shadows). */
export function areaLamp(room: RoomBox): { width: number; depth: number; position: THREE.Vector3 } {
  return {
    width: room.halfWidth * 1.2,
    depth: room.halfDepth * 1.2,
    position: new THREE.Vector3(room.halfWidth * 0.3, room.top + 1.5, room.halfDepth * 0.45),
  };
}

/** The warm fill lamp low in the far corner, the same light in both views; brighter in a larger room. */
export function placeFillLamp(fill: THREE.PointLight, room: RoomBox): void {
  fill.color.set(0xffe2c0);
  fill.intensity = 2 * Math.max(1, (room.halfWidth * room.halfDepth) / 9);
  fill.distance = 0;
  fill.decay = 1.6;
  fill.position.set(-room.halfWidth * 0.4, room.top * 0.8, -room.halfDepth * 0.3);
}

/** The live view's lights, added to its scene; `fit` places them for a room. */
export interface LiveLights {
  /** The key light: the only one that casts shadows. */
  sun: THREE.DirectionalLight;
  fill: THREE.PointLight;
  fit(room: RoomBox): void;
}

/** Adds the live view's lights to `scene`, fitted to a 6 m room until `fit` is called. */
export function addLiveLights(scene: THREE.Scene): LiveLights {
  scene.add(new THREE.HemisphereLight(SKY.above, SKY.below, HEMISPHERE_INTENSITY));

  const sun = new THREE.DirectionalLight(LAMP_COLOR, KEY_INTENSITY);
  sun.castShadow = true;
  sun.shadow.mapSize.set(2048, 2048);
  // Texels the PCF filter's taps spread over: a soft edge.
  sun.shadow.radius = 6;
  sun.shadow.bias = -0.0004;
  sun.shadow.normalBias = 0.02;
  scene.add(sun, sun.target);

  const fill = new THREE.PointLight();
  scene.add(fill);

  function fit(room: RoomBox): void {
    const reach = Math.hypot(room.halfWidth, room.halfDepth, room.top) * 1.2;
    sun.position.copy(keyLightPosition(room));
    sun.target.position.set(0, 0, 0);
    const cam = sun.shadow.camera;
    cam.left = -reach;
    cam.right = reach;
    cam.top = reach;
    cam.bottom = -reach;
    cam.near = 0.1;
    cam.far = room.top * 4 + reach * 2;
    cam.updateProjectionMatrix();
    placeFillLamp(fill, room);
  }

  fit({ halfWidth: 3, halfDepth: 3, top: 4.5 });
  return { sun, fill, fit };
}
