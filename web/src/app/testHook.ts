// The end-to-end tests' view into the app, `window.__up`: it reads state and
// the rendered pixels, and never drives the app (the tests use the same keys
// and clicks as a user). main.ts loads this module only when the page's
// address has the `test` parameter (`/?test#scene=…`), so a visitor's page
// neither downloads it nor exposes the hook.

import * as THREE from "three";
import { POSE_STRIDE } from "../render/poseMath";
import type { App } from "./app";

export function createTestHook(app: App) {
  const { bridge, controls, messages, world } = app;
  const { renderer, scene, camera } = app.stage;
  return {
    ready: () => app.ready,
    balloonCount: () => bridge.current?.count ?? 0,
    poses: () => Array.from(bridge.curr),
    paused: () => bridge.paused,
    /** Frames drawn with balloons, and main-thread ms spent in renderer.render over them. */
    frames: () => ({ ...app.frames }),
    /** The worker's last stats (stage ms per step, counts) and its steps per second. */
    stats: () => app.lastStats,
    debugView: () => world.debug.visible,
    /** Contacts the debug view draws now, and how many the current frame carried. */
    contacts: () => ({
      drawn: world.debug.visible ? world.debug.contactCount : 0,
      inFrame: bridge.current?.contactCount ?? 0,
      total: bridge.current?.contactTotal ?? 0,
    }),
    placement: () => controls.placement,
    steps: () => bridge.current?.steps ?? 0,
    version: () => bridge.current?.version ?? -1,
    sceneJson: () => JSON.stringify(app.scene),
    messages: () => messages.shown.slice(),
    camera: () => ({ position: camera.position.toArray(), target: controls.center().toArray() }),
    /** World centre of balloon i's root sphere (what a click should aim at). */
    balloonCenter(i: number): [number, number, number] | null {
      const p = bridge.curr;
      const root = app.info?.trees[bridge.models[i] ?? 0]?.[0];
      const at = i * POSE_STRIDE;
      if (!root || p.length < at + POSE_STRIDE) return null;
      const q = new THREE.Quaternion(p[at + 3], p[at + 4], p[at + 5], p[at + 6]);
      const c = new THREE.Vector3(...root.center).applyQuaternion(q).add(new THREE.Vector3(p[at], p[at + 1], p[at + 2]));
      return [c.x, c.y, c.z];
    },
    /** Client pixel coordinates of a world point. */
    project(x: number, y: number, z: number) {
      const v = new THREE.Vector3(x, y, z).project(camera);
      const rect = renderer.domElement.getBoundingClientRect();
      return { x: rect.left + ((v.x + 1) / 2) * rect.width, y: rect.top + ((1 - v.y) / 2) * rect.height };
    },
    /** Renders once and measures the picture: how varied, how much saturated colour. */
    pixelStats(hideBalloons = false) {
      const balloons = world.balloons;
      if (hideBalloons && balloons) balloons.setVisible(false);
      renderer.render(scene, camera);
      if (hideBalloons && balloons) balloons.setVisible(true);
      const gl = renderer.getContext();
      const w = gl.drawingBufferWidth;
      const h = gl.drawingBufferHeight;
      const px = new Uint8Array(w * h * 4);
      gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, px);
      let sum = 0;
      let sum2 = 0;
      let saturated = 0;
      for (let i = 0; i < px.length; i += 4) {
        const r = px[i];
        const g = px[i + 1];
        const b = px[i + 2];
        const l = 0.2126 * r + 0.7152 * g + 0.0722 * b;
        sum += l;
        sum2 += l * l;
        const max = Math.max(r, g, b);
        const min = Math.min(r, g, b);
        if (max > 60 && (max - min) / max > 0.5) saturated++;
      }
      const n = w * h;
      const mean = sum / n;
      return { width: w, height: h, mean, std: Math.sqrt(Math.max(0, sum2 / n - mean * mean)), saturatedFraction: saturated / n, pixels: n };
    },
  };
}

export type TestHook = ReturnType<typeof createTestHook>;

declare global {
  interface Window {
    /** Present only on pages opened with `?test`. */
    __up?: TestHook;
  }
}

export function installTestHook(app: App): void {
  window.__up = createTestHook(app);
}
