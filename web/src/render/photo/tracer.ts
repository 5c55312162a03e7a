// The path tracer as photo mode sets it up (three-gpu-pathtracer's
// WebGLPathTracer on the page's own WebGL renderer): bounces, tiles, the
// live view shown until the first sample is whole, and a light edge-aware
// denoiser (the library's DenoiseMaterial, a smart Gaussian) over the first
// samples. Loaded with the first photo (photoMode.ts imports it on demand).

import * as THREE from "three";
import { FullScreenQuad } from "three/examples/jsm/postprocessing/Pass.js";
import { DenoiseMaterial, WebGLPathTracer } from "three-gpu-pathtracer";

export { addPhotoLights } from "./photoLights";

/** Light bounces (and more through transmissive surfaces): the room's walls, ceiling and balloons light each other. */
const BOUNCES = 5;
const TRANSMISSIVE_BOUNCES = 4;
/** Tiles across and down a sample is split into, one per animation frame: the page keeps answering while it traces. */
export const TILES = 3;
/**
 * Samples after which the denoiser is off: by then the samples themselves
 * are smooth and the filter would only blur. The 256 is a judgement by eye,
 * not a measurement.
 */
const DENOISE_UNTIL = 256;

/** A path tracer on `renderer`; until its first whole sample, `fallback` draws the canvas. */
export function makeTracer(renderer: THREE.WebGLRenderer, fallback: () => void): WebGLPathTracer {
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
  tracer.rasterizeSceneCallback = fallback;
  const denoise = new FullScreenQuad(new DenoiseMaterial({ sigma: 3, kSigma: 1.5, threshold: 0.25 }));
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
  return tracer;
}
