// Photo mode (key P, the panel's photo button): the simulation pauses, the
// scene drawn now is baked (bake.ts) and handed to three-gpu-pathtracer, and
// the picture refines in the page, one tile of a sample per animation frame
// so the page keeps answering; a light edge-aware denoiser (the tracer's
// DenoiseMaterial) smooths the first samples' grain. Save downloads the
// canvas as a PNG. Any key but a modifier, or the button again, goes back to
// the live view as it was, running again if it ran before.

import * as THREE from "three";
import { FullScreenQuad } from "three/examples/jsm/postprocessing/Pass.js";
import { DenoiseMaterial, WebGLPathTracer } from "three-gpu-pathtracer";
import { bakeScene, type Bake, type RibbonSource } from "./bake";
import { addPhotoLights, type RoomBox } from "./photoLights";
import { downloadBlob, timestampName } from "./download";

/** What photo mode needs of the app. */
export interface PhotoHost {
  renderer: THREE.WebGLRenderer;
  scene: THREE.Scene;
  camera: THREE.PerspectiveCamera;
  /** Parts of the live scene the photo leaves out (the debug view). */
  exclude: THREE.Object3D[];
  room(): RoomBox;
  /** The ribbons as drawn now, or null. */
  ribbons(): RibbonSource | null;
  paused(): boolean;
  setPaused(paused: boolean): void;
  /** Photo mode was entered or left, or its sample count changed. */
  changed(state: PhotoState): void;
}

export interface PhotoState {
  active: boolean;
  /** Whole samples per pixel traced so far. */
  samples: number;
}

/** Light bounces (and more through transmissive surfaces): the room's walls, ceiling and balloons light each other. */
const BOUNCES = 5;
const TRANSMISSIVE_BOUNCES = 4;
/** Tiles a sample is split into (one per animation frame): a SwiftShader frame stays near a second at 960×600. */
const TILES = 3;
/** Latex's transmission in the photo when the live material has none: physics-reference "Looks" infers 0.2–0.4 (a guess), thin film. */
const LATEX_TRANSMISSION = 0.2;
/** Samples after which the denoiser is off: by then the samples themselves are smooth, and the filter only blurs. */
const DENOISE_UNTIL = 256;

/** Keys that never leave photo mode (modifiers held for something else). */
const MODIFIER_KEYS = new Set(["Control", "Shift", "Alt", "Meta", "AltGraph", "CapsLock", "Fn", "NumLock", "ScrollLock", "OS"]);

export class PhotoMode {
  active = false;
  /** The last bake's duration, ms, its instances and triangles (measurements). */
  lastBake = { ms: 0, instances: 0, triangles: 0 };
  private tracer: WebGLPathTracer | null = null;
  private bake: Bake | null = null;
  private lights: { dispose(): void } | null = null;
  private camera: THREE.PerspectiveCamera | null = null;
  private wasPaused = false;
  private shownSamples = -1;

  constructor(private readonly host: PhotoHost) {
    // Capture phase on the window: photo mode sees keys and canvas presses before the controls do.
    window.addEventListener("keydown", (e) => this.keyDown(e), { capture: true });
    const canvas = host.renderer.domElement;
    for (const type of ["pointerdown", "pointermove", "pointerup", "wheel", "dblclick"]) {
      window.addEventListener(
        type,
        (e) => {
          // The camera stays where the photo was taken; the panel's buttons still work.
          if (this.active && e.target === canvas) e.stopImmediatePropagation();
        },
        { capture: true },
      );
    }
  }

  get samples(): number {
    return this.tracer && this.active ? Math.floor(this.tracer.samples) : 0;
  }

  toggle(): void {
    if (this.active) this.exit();
    else this.enter();
  }

  /** Pauses, bakes the scene drawn now and starts tracing it. */
  enter(): void {
    if (this.active) return;
    const host = this.host;
    this.wasPaused = host.paused();
    host.setPaused(true);
    const start = performance.now();
    const bake = bakeScene(host.scene, host.exclude, host.ribbons());
    for (const o of bake.scene.children) {
      const material = (o as THREE.Mesh).material as THREE.MeshPhysicalMaterial | undefined;
      if (o.name === "balloons" && material?.isMeshPhysicalMaterial && material.transmission === 0) material.transmission = LATEX_TRANSMISSION;
    }
    this.lights = addPhotoLights(bake.scene, host.room(), host.scene.background instanceof THREE.Color ? host.scene.background : null);
    this.camera = host.camera.clone();
    const tracer = this.makeTracer();
    tracer.setScene(bake.scene, this.camera);
    this.bake = bake;
    this.lastBake = { ms: performance.now() - start, instances: bake.instances, triangles: bake.triangles };
    this.active = true;
    this.shownSamples = -1;
    this.report();
  }

  /** Back to the live view, running again if it ran before. */
  exit(): void {
    if (!this.active) return;
    this.active = false;
    this.bake?.dispose();
    this.lights?.dispose();
    this.bake = null;
    this.lights = null;
    // The tracer keeps its compiled shader for the next photo; only its picture goes.
    this.tracer?.reset();
    this.host.setPaused(this.wasPaused);
    this.report();
  }

  /** One animation frame in photo mode: a tile of the next sample, and the picture so far on the canvas. */
  render(): void {
    const tracer = this.tracer;
    const camera = this.camera;
    if (!this.active || !tracer || !camera) return;
    // A resized page changes the live camera's aspect: follow it (the picture starts over).
    if (camera.aspect !== this.host.camera.aspect) {
      camera.aspect = this.host.camera.aspect;
      camera.updateProjectionMatrix();
      tracer.setCamera(camera);
    }
    tracer.renderSample();
    this.report();
  }

  /** Draws the picture so far on the canvas again, without tracing more: for reading the canvas in the same task. */
  redraw(): void {
    const tracer = this.tracer;
    if (!this.active || !tracer) return;
    tracer.pausePathTracing = true;
    tracer.renderSample();
    tracer.pausePathTracing = false;
  }

  /** Downloads the picture as a PNG of the canvas's size. */
  save(): void {
    if (!this.active) return;
    // The drawing buffer is not preserved between frames: draw, then read it in the same task.
    this.redraw();
    this.host.renderer.domElement.toBlob((blob) => {
      if (blob) downloadBlob(blob, timestampName("up-photo", "png"));
    }, "image/png");
  }

  private makeTracer(): WebGLPathTracer {
    if (this.tracer) return this.tracer;
    const renderer = this.host.renderer;
    const tracer = new WebGLPathTracer(renderer);
    tracer.bounces = BOUNCES;
    tracer.transmissiveBounces = TRANSMISSIVE_BOUNCES;
    tracer.multipleImportanceSampling = true;
    // Caps a glossy bounce's roughness from the second bounce on: fewer fireflies in the clearcoat.
    tracer.filterGlossyFactor = 0.5;
    tracer.tiles.set(TILES, TILES);
    tracer.renderDelay = 0;
    tracer.minSamples = 1;
    tracer.fadeDuration = 0;
    // Until the first sample is whole, the live view stays on the canvas.
    tracer.rasterizeSceneCallback = () => renderer.render(this.host.scene, this.host.camera);
    const denoise = new FullScreenQuad(new DenoiseMaterial({ sigma: 2.5, kSigma: 1.5, threshold: 0.12 }));
    tracer.renderToCanvasCallback = (target, r, quad) => {
      const autoClear = r.autoClear;
      r.autoClear = false;
      if (tracer.samples < DENOISE_UNTIL) {
        (denoise.material as DenoiseMaterial).map = target.texture;
        denoise.render(r);
      } else {
        quad.render(r);
      }
      r.autoClear = autoClear;
    };
    this.tracer = tracer;
    return tracer;
  }

  private keyDown(e: KeyboardEvent): void {
    if (!this.active) return;
    // Nothing else sees the key (a held CTRL would toggle placement mode behind the photo).
    e.stopImmediatePropagation();
    if (MODIFIER_KEYS.has(e.key) || e.repeat) return;
    e.preventDefault();
    this.exit();
  }

  private report(): void {
    const samples = this.samples;
    if (this.active && samples === this.shownSamples) return;
    this.shownSamples = samples;
    this.host.changed({ active: this.active, samples });
  }
}
