// The three.js stage: renderer, camera, lights, environment map and shadows.

import * as THREE from "three";
import { RoomEnvironment } from "three/examples/jsm/environments/RoomEnvironment.js";

export interface Stage {
  renderer: THREE.WebGLRenderer;
  scene: THREE.Scene;
  camera: THREE.PerspectiveCamera;
  sun: THREE.DirectionalLight;
  /** Fits the shadow camera and light to a room of this half-size and height, m. */
  fitToRoom(halfWidth: number, halfDepth: number, height: number): void;
  resize(): void;
}

/** Whether this browser can give a WebGL 2 context at all. */
export function hasWebGL(): boolean {
  try {
    const canvas = document.createElement("canvas");
    return !!canvas.getContext("webgl2");
  } catch {
    return false;
  }
}

export function createStage(container: HTMLElement): Stage {
  const renderer = new THREE.WebGLRenderer({ antialias: true, powerPreference: "high-performance" });
  renderer.setPixelRatio(Math.min(window.devicePixelRatio, 2));
  renderer.outputColorSpace = THREE.SRGBColorSpace;
  renderer.toneMapping = THREE.ACESFilmicToneMapping;
  renderer.toneMappingExposure = 1.0;
  renderer.shadowMap.enabled = true;
  renderer.shadowMap.type = THREE.PCFSoftShadowMap;
  renderer.domElement.id = "view";
  container.appendChild(renderer.domElement);

  const scene = new THREE.Scene();
  scene.background = new THREE.Color(0x1d2230);

  // Image-based lighting for the latex's reflections and clearcoat.
  const pmrem = new THREE.PMREMGenerator(renderer);
  const environment = new RoomEnvironment();
  scene.environment = pmrem.fromScene(environment, 0.04).texture;
  scene.environmentIntensity = 0.55;
  environment.dispose();
  pmrem.dispose();

  const camera = new THREE.PerspectiveCamera(45, 1, 0.05, 500);

  scene.add(new THREE.HemisphereLight(0xfff6e8, 0x40362c, 0.6));

  // The "sun" stands for the ceiling lamps: one soft-shadowed key light from above.
  const sun = new THREE.DirectionalLight(0xfff1dc, 2.2);
  sun.castShadow = true;
  sun.shadow.mapSize.set(2048, 2048);
  sun.shadow.radius = 6;
  sun.shadow.blurSamples = 16;
  sun.shadow.bias = -0.0004;
  sun.shadow.normalBias = 0.02;
  scene.add(sun, sun.target);

  const fill = new THREE.PointLight(0xffe2c0, 6, 0, 1.6);
  scene.add(fill);

  function fitToRoom(halfWidth: number, halfDepth: number, height: number): void {
    const reach = Math.hypot(halfWidth, halfDepth, height) * 1.2;
    sun.position.set(halfWidth * 0.6, height * 2.2, halfDepth * 0.9);
    sun.target.position.set(0, 0, 0);
    const cam = sun.shadow.camera;
    cam.left = -reach;
    cam.right = reach;
    cam.top = reach;
    cam.bottom = -reach;
    cam.near = 0.1;
    cam.far = height * 4 + reach * 2;
    cam.updateProjectionMatrix();
    fill.position.set(-halfWidth * 0.4, height * 0.8, -halfDepth * 0.3);
    fill.distance = 0;
    fill.intensity = 2 * Math.max(1, (halfWidth * halfDepth) / 9);
  }

  function resize(): void {
    const w = container.clientWidth || window.innerWidth;
    const h = container.clientHeight || window.innerHeight;
    renderer.setSize(w, h, false);
    camera.aspect = w / Math.max(1, h);
    camera.updateProjectionMatrix();
  }

  resize();
  return { renderer, scene, camera, sun, fitToRoom, resize };
}
