// The three.js stage: renderer, camera, environment map and shadows; the
// lights themselves are the room's (roomLights.ts, shared with the photo).

import * as THREE from "three";
import { RoomEnvironment } from "three/examples/jsm/environments/RoomEnvironment.js";
import { addLiveLights, BACKGROUND_COLOR, ENVIRONMENT_INTENSITY } from "./roomLights";

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

/** What the stage may spend (drawingBudget.ts): device pixels per CSS pixel and the shadow map's size. */
export interface StageBudget {
  pixelRatioCap: number;
  shadowMapSize: number;
}

export function createStage(container: HTMLElement, budget: StageBudget = { pixelRatioCap: 2, shadowMapSize: 2048 }): Stage {
  const renderer = new THREE.WebGLRenderer({ antialias: true, powerPreference: "high-performance" });
  renderer.setPixelRatio(Math.min(window.devicePixelRatio, budget.pixelRatioCap));
  renderer.outputColorSpace = THREE.SRGBColorSpace;
  renderer.toneMapping = THREE.ACESFilmicToneMapping;
  renderer.toneMappingExposure = 1.0;
  renderer.shadowMap.enabled = true;
  // PCF filtered over the key light's shadow radius: soft edges (three.js dropped PCFSoftShadowMap for this).
  renderer.shadowMap.type = THREE.PCFShadowMap;
  renderer.domElement.id = "view";
  container.appendChild(renderer.domElement);

  const scene = new THREE.Scene();
  scene.background = new THREE.Color(BACKGROUND_COLOR);

  // Image-based lighting for the latex's reflections and clearcoat.
  const pmrem = new THREE.PMREMGenerator(renderer);
  const environment = new RoomEnvironment();
  scene.environment = pmrem.fromScene(environment, 0.04).texture;
  scene.environmentIntensity = ENVIRONMENT_INTENSITY;
  environment.dispose();
  pmrem.dispose();

  const camera = new THREE.PerspectiveCamera(45, 1, 0.05, 500);

  const lights = addLiveLights(scene);
  lights.sun.shadow.mapSize.set(budget.shadowMapSize, budget.shadowMapSize);

  function fitToRoom(halfWidth: number, halfDepth: number, height: number): void {
    lights.fit({ halfWidth, halfDepth, top: height });
  }

  function resize(): void {
    const w = container.clientWidth || window.innerWidth;
    const h = container.clientHeight || window.innerHeight;
    renderer.setSize(w, h, false);
    camera.aspect = w / Math.max(1, h);
    camera.updateProjectionMatrix();
  }

  resize();
  return { renderer, scene, camera, sun: lights.sun, fitToRoom, resize };
}
