// The end-to-end tests' reads of photo mode and the clip recorder (part of
// `window.__up`, testHook.ts): their state, and the canvas's pixels kept
// under a name in the page, so that two pictures are compared there rather
// than shipped to the test as arrays.

import type { App } from "./app";
import { brightness, meanAbsDifference } from "../render/photo/pixels";

export function photoTestHook(app: App) {
  const kept = new Map<string, Uint8Array>();
  return {
    /** Photo mode: on or off, whole samples so far, the last bake's ms, instances and triangles. */
    photo: () => ({ active: app.photo.active, samples: app.photo.samples, bake: { ...app.photo.lastBake } }),
    /** Whether a clip is recording, the clips saved so far (type, bytes), and the takes that had no frames to save. */
    recording: () => ({ recording: app.recorder.recording, saved: app.recorder.saved.slice(), empty: app.recorder.empty }),
    /**
     * Draws the view once more (the photo so far, or a live frame) and keeps
     * its pixels as `name`; returns its size, mean luminance (0–255) and
     * share of pure black pixels.
     */
    keepPixels(name: string) {
      const { renderer, scene, camera } = app.stage;
      if (app.photo.active) app.photo.redraw();
      else renderer.render(scene, camera);
      const gl = renderer.getContext();
      const w = gl.drawingBufferWidth;
      const h = gl.drawingBufferHeight;
      const px = new Uint8Array(w * h * 4);
      gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, px);
      kept.set(name, px);
      return { width: w, height: h, ...brightness(px) };
    },
    /** Mean absolute RGB difference of two kept pictures, 0–255. */
    pixelDifference: (a: string, b: string) => meanAbsDifference(kept.get(a) ?? new Uint8Array(0), kept.get(b) ?? new Uint8Array(0)),
  };
}
