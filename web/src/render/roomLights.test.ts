import { describe, expect, it } from "vitest";
import * as THREE from "three";
import { addLiveLights, ENVIRONMENT_INTENSITY, type RoomBox } from "./roomLights";
import { addPhotoLights } from "./photo/photoLights";

const ROOMS: RoomBox[] = [
  { halfWidth: 3, halfDepth: 3, top: 4.5 },
  { halfWidth: 10, halfDepth: 4, top: 3 },
];

/** To a micrometre: positions compared as numbers written in the code. */
const rounded = (v: THREE.Vector3) => v.toArray().map((x) => Math.round(x * 1e6) / 1e6);

function lightsOf<T extends THREE.Light>(scene: THREE.Scene, type: new (...args: never[]) => T): T[] {
  return scene.children.filter((c): c is T => c instanceof type);
}

describe("the room's lights", () => {
  it("light the photo with the live view's fill lamp, lamp colour, sky colours and environment strength", () => {
    for (const room of ROOMS) {
      const live = new THREE.Scene();
      const lights = addLiveLights(live);
      lights.fit(room);
      const photo = new THREE.Scene();
      const { dispose } = addPhotoLights(photo, room, null);

      const [liveFill] = lightsOf(live, THREE.PointLight);
      const [photoFill] = lightsOf(photo, THREE.PointLight);
      expect(photoFill.position.toArray()).toEqual(liveFill.position.toArray());
      expect(photoFill.color.getHex()).toBe(liveFill.color.getHex());
      expect([photoFill.intensity, photoFill.decay, photoFill.distance]).toEqual([liveFill.intensity, liveFill.decay, liveFill.distance]);

      const [lamp] = lightsOf(photo, THREE.RectAreaLight);
      expect(lamp.color.getHex(), "the photo's lamp is the live key light's colour").toBe(lights.sun.color.getHex());
      const [hemisphere] = lightsOf(live, THREE.HemisphereLight);
      const sky = photo.environment as THREE.Texture & { topColor: THREE.Color; bottomColor: THREE.Color };
      expect(sky.topColor.getHex()).toBe(hemisphere.color.getHex());
      expect(sky.bottomColor.getHex()).toBe(hemisphere.groundColor.getHex());
      expect(photo.environmentIntensity).toBe(ENVIRONMENT_INTENSITY);
      dispose();
    }
  });

  it("keep the photo's lamps where they were fitted to a 6 m room", () => {
    const photo = new THREE.Scene();
    addPhotoLights(photo, ROOMS[0], new THREE.Color(0x102030)).dispose();
    const [lamp] = lightsOf(photo, THREE.RectAreaLight);
    expect(rounded(lamp.position)).toEqual([0.9, 6, 1.35]);
    expect(lamp.width).toBeCloseTo(3.6, 9);
    expect(lamp.height).toBeCloseTo(3.6, 9);
    expect(lamp.intensity).toBe(9);
    // Facing straight down onto the floor (three aims a light's −z at what it looks at).
    lamp.updateMatrixWorld();
    expect(new THREE.Vector3(0, 0, -1).transformDirection(lamp.matrixWorld).y).toBeCloseTo(-1, 6);
    const [fill] = lightsOf(photo, THREE.PointLight);
    expect(rounded(fill.position)).toEqual([-1.2, 3.6, -0.9]);
    expect(fill.intensity).toBe(2);
    expect((photo.background as THREE.Color).getHex(), "the live view's background").toBe(0x102030);
  });

  it("fit the live key light's shadow camera around the room", () => {
    const live = new THREE.Scene();
    const { sun, fit } = addLiveLights(live);
    fit(ROOMS[1]);
    expect(sun.castShadow).toBe(true);
    expect(rounded(sun.position)).toEqual([6, 6.6, 3.6]);
    const reach = Math.hypot(10, 4, 3) * 1.2;
    expect(sun.shadow.camera.right).toBeCloseTo(reach, 9);
    expect(sun.shadow.camera.far).toBeCloseTo(12 + 2 * reach, 9);
  });
});
