// Photo mode (key P, the panel's photo button): the simulation pauses, the
// scene drawn now is baked (bake.ts) and handed to three-gpu-pathtracer
// (tracer.ts), and the picture refines in the page, one tile of a sample per
// animation frame so the page keeps answering. Save downloads the canvas as
// a PNG. Any key but a modifier, or the button again, goes back to the live
// view as it was, running again if it ran before.

import * as THREE from "three";
import type { WebGLPathTracer } from "three-gpu-pathtracer";
import { bakeScene, type Bake, type RibbonSource } from "./bake";
import type { RoomBox } from "./photoLights";
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
  /** The tracer failed to load. */
  error(message: string): void;
}

export interface PhotoState {
  active: boolean;
  /** Whole samples per pixel traced so far. */
  samples: number;
}

/** Latex's transmission in the photo when the live material has none: physics-reference "Looks" infers 0.2–0.4 (a guess), as a thin film. */
const LATEX_TRANSMISSION = 0.2;

/** Keys that never leave photo mode (modifiers, held for something else). */
const MODIFIER_KEYS = new Set(["Control", "Shift", "Alt", "Meta", "AltGraph", "CapsLock", "Fn", "NumLock", "ScrollLock", "OS"]);

export class PhotoMode {
  active = false;
  /**
   * The last bake (measurements): ms in all, ms of it merging the meshes (the
   * rest is the tracer's BVH and material tables), instances and triangles.
   */
  lastBake = { ms: 0, mergeMs: 0, instances: 0, triangles: 0 };
  private module: Promise<typeof import("./tracer")> | null = null;
  private tracer: WebGLPathTracer | null = null;
  private bake: Bake | null = null;
  private lights: { dispose(): void } | null = null;
  private camera: THREE.PerspectiveCamera | null = null;
  private wasPaused = false;
  private shownSamples = -1;
  /** Bumped by every enter and exit: a load that finishes after the photo was left does nothing. */
  private generation = 0;

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

  /** Pauses, bakes the scene drawn now and starts tracing it (the tracer loads with the first photo). */
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
    const bakeMs = performance.now() - start;
    this.bake = bake;
    this.camera = host.camera.clone();
    this.active = true;
    this.shownSamples = -1;
    const generation = ++this.generation;
    this.module ??= import("./tracer");
    this.module.then(
      (lib) => {
        if (generation !== this.generation) return;
        const t0 = performance.now();
        this.lights = lib.addPhotoLights(bake.scene, host.room(), host.scene.background instanceof THREE.Color ? host.scene.background : null);
        this.tracer ??= lib.makeTracer(host.renderer, () => host.renderer.render(host.scene, host.camera));
        this.tracer.setScene(bake.scene, this.camera!);
        // The bake: instances merged, and the tracer's BVH and material textures built from them.
        this.lastBake = { ms: bakeMs + performance.now() - t0, mergeMs: bakeMs, instances: bake.instances, triangles: bake.triangles };
        this.report();
      },
      (e: Error) => {
        this.host.error(`Photo mode could not load its path tracer: ${e.message}`);
        this.exit();
      },
    );
    this.report();
  }

  /** Back to the live view, running again if it ran before. */
  exit(): void {
    if (!this.active) return;
    this.active = false;
    this.generation++;
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
    if (!this.active) return;
    if (!tracer || !camera || !this.lights) {
      // The tracer is still loading: the live view stays.
      this.host.renderer.render(this.host.scene, this.host.camera);
      return;
    }
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
    if (!this.active) return;
    if (!tracer || !this.lights) {
      this.host.renderer.render(this.host.scene, this.host.camera);
      return;
    }
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
    this.shownSamples = this.active ? samples : -1;
    this.host.changed({ active: this.active, samples });
  }
}
