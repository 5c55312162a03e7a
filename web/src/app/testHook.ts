// The end-to-end tests' view into the app, `window.__up`: it reads state and
// the rendered pixels, and never drives the app (the tests use the same keys
// and clicks as a user), but for `measureSteps`, the timed step window of
// `make measure`. main.ts loads this module only when the page's
// address has the `test` parameter (`/?test#scene=…`), so a visitor's page
// neither downloads it nor exposes the hook.

import * as THREE from "three";
import { POSE_STRIDE } from "../sim/poseLayout";
import { PLOT_COLORS } from "../ui/floatPlot";
import type { App } from "./app";
import { photoTestHook } from "./photoTestHook";

export function createTestHook(app: App) {
  const { bridge, controls, messages, world } = app;
  const { renderer, scene, camera } = app.stage;
  return {
    ...photoTestHook(app),
    ready: () => app.ready,
    balloonCount: () => bridge.current?.count ?? 0,
    poses: () => Array.from(bridge.curr),
    paused: () => bridge.paused,
    /** Frames drawn with balloons, and main-thread ms spent in renderer.render over them. */
    frames: () => ({ ...app.frames }),
    /** The worker's last stats (stage ms per step, counts) and its steps per second. */
    stats: () => app.lastStats,
    /** Measurements (make measure): the main thread's frame work and render call, and a reset to start a window. */
    frameMeter: () => app.frameMeter.summary(),
    resetFrameMeter: () => app.frameMeter.reset(),
    /** Measurements: the scene restarted and `steps` steps timed in the worker (each thread's part of each stage too when `threadTimes`); resolves with the times and the state hash. */
    measureSteps: (steps: number, threadTimes = false) => app.bridge.measureSteps(steps, threadTimes),
    /** Measurements: balloons and their ribbons drawn or not (the frame's work goes on; SwiftShader's drawing of thousands takes the CPU). */
    drawBalloons: (on: boolean) => {
      world.balloons?.setVisible(on);
      if (world.ribbons) world.ribbons.group.visible = on;
    },
    /** Measurements: frames that do nothing (the GPU gets nothing to draw), or their work again (`App.drawingHeld`). */
    holdDrawing: (held: boolean) => {
      app.drawingHeld = held;
    },
    /**
     * Measurements: returns once the GPU has finished every frame sent so far
     * (SwiftShader takes seconds over a frame of thousands of balloons, on the
     * CPU, after the render call has returned).
     */
    finishDrawing: () => renderer.getContext().finish(),
    debugView: () => world.debug.visible,
    /** Contacts the debug view draws now, and how many the current frame carried. */
    contacts: () => ({
      drawn: world.debug.visible ? world.debug.contactCount : 0,
      inFrame: bridge.current?.contactCount ?? 0,
      total: bridge.current?.contactTotal ?? 0,
    }),
    placement: () => controls.placement,
    /** The layout (layout.ts), whose turn the bottom corner is, whether the panel is folded and the HUD opened. */
    layout: () => ({
      ...app.layout.layout,
      bottom: app.layout.bottom,
      panelClosed: app.panel?.gui.domElement.classList.contains("lil-closed") ?? null,
      hudExpanded: app.hud.expanded,
    }),
    /** What a frame may cost here (drawingBudget.ts) and whether the crowd mesh draws the balloons now. */
    budget: () => ({ ...app.budget, crowdDrawn: world.balloons?.crowdDrawn ?? false, hud: document.getElementById("hud-cost")?.textContent ?? "" }),
    /** The first paint and the first frame drawn with balloons, ms on the page's clock (null: not yet). */
    firstDraw: () => ({ firstPaint: performance.getEntriesByName("first-paint")[0]?.startTime ?? null, firstDrawAt: app.firstDrawAt, ...app.startup }),
    /** Ribbons in the current frame, and those the renderer draws. */
    ribbonCount: () => bridge.ribbons.bodies.length,
    ribbonsDrawn: () => world.ribbons?.count ?? 0,
    /** Ribbon particles the debug view shows now. */
    ribbonParticlesDrawn: () => (world.debug.visible ? world.debug.ribbonPointCount : 0),
    /** Ribbon r's free end (world, m) and the dense index of its balloon, or null. */
    ribbonEnd(r: number): { end: [number, number, number]; body: number } | null {
      const { offsets, bodies } = bridge.ribbons;
      if (r < 0 || r >= bodies.length) return null;
      const e = (offsets[r + 1] - 1) * 3;
      const p = bridge.ribbonsCurr;
      if (p.length < e + 3) return null;
      return { end: [p[e], p[e + 1], p[e + 2]], body: bodies[r] };
    },
    /** Every ribbon's points in the current frame (x, y, z each, the knot first), each ribbon's first point (then the total) and balloon: what the engine's `ribbon_linking` reads. */
    ribbonPoints: () => ({ points: Array.from(bridge.ribbonsCurr), offsets: Array.from(bridge.ribbons.offsets), bodies: Array.from(bridge.ribbons.bodies) }),
    steps: () => bridge.current?.steps ?? 0,
    /** Threads stepping the engine (0 before it is ready), and whether the page is cross-origin isolated. */
    threads: () => app.info?.threads ?? 0,
    isolated: () => app.info?.isolated ?? null,
    /** What the HUD's threads line reads. */
    threadsText: () => document.getElementById("hud-threads")?.textContent ?? "",
    /** The world's state hash (16 hex digits, as `up run --json` prints it) and the steps it was taken after. */
    stateHash: () => bridge.stateHash(),
    /** The simulated clock of the current frame and what the HUD's clock line reads. */
    clock: () => {
      const f = bridge.current;
      return {
        simTime: f?.simTime ?? 0,
        airTemperatureC: f?.airTemperatureC ?? NaN,
        rate: f?.rate ?? 1,
        achievedRate: f?.achievedRate ?? 0,
        text: document.getElementById("hud-clock")?.textContent ?? "",
      };
    },
    /**
     * The foil balloons: InstancedMeshes named "foil-balloons" in the scene
     * graph and the instances they draw, and the dense indices of the
     * frame's bodies whose model is foil.
     */
    foil() {
      let meshes = 0;
      let drawn = 0;
      scene.traverse((o) => {
        const mesh = o as THREE.InstancedMesh;
        if (mesh.isInstancedMesh && mesh.name === "foil-balloons") {
          meshes++;
          drawn += mesh.count;
        }
      });
      const isFoil = app.info?.foilMeshes.map((m) => m !== null) ?? [];
      const bodies: number[] = [];
      bridge.models.forEach((m, i) => {
        if (isFoil[m]) bodies.push(i);
      });
      return { meshes, drawn, bodies };
    },
    /** Each body's size over its shape's in the current frame (its gas's). */
    bodyScales: () => Array.from(bridge.scales),
    /** The latex meshes by finish (material type and the uniforms that tell them apart, bodies drawn), and the panel's override. */
    finishes: () => ({ meshes: world.balloons?.finishesDrawn() ?? [], override: world.balloons?.finishOverride ?? null, scene: app.info?.finishes ?? [] }),
    /**
     * Body i's dent: as drawn now, and as it would be drawn `agesMs` after
     * it was made (the normal times the depth, m, world, and the reach, m;
     * zeros: round), and when it was made (ms since the epoch; null: none).
     */
    squash: (i: number, agesMs: number[] = []) => ({
      drawn: world.balloons?.squashOf(i) ?? [0, 0, 0, 0],
      at: agesMs.map((ms) => world.balloons?.squashAt(i, ms) ?? [0, 0, 0, 0]),
      madeAt: world.balloons?.dents.madeAt(i) ?? null,
    }),
    /** Body i's deepest dent since its balloons were set, as `squash` gives a dent (`SquashDents.peak`). */
    squashPeak: (i: number, agesMs: number[] = []) => world.balloons?.dents.peak(i, agesMs) ?? { at: [], madeAt: null },
    /**
     * The float plot's samples, and the pixels of its lines' area (the
     * legend and the axis's words left out): those of a line (neither
     * background nor grid), and those of the ceiling's line.
     */
    plot() {
      const { canvas, area } = app.plot;
      const ratio = canvas.width / canvas.clientWidth;
      const ctx = canvas.getContext("2d");
      const hex = (h: string) => [1, 3, 5].map((i) => parseInt(h.slice(i, i + 2), 16));
      const [br, bg, bb] = hex(PLOT_COLORS.background);
      const [gr, gg, gb] = hex(PLOT_COLORS.grid);
      const [cr, cg, cb] = hex(PLOT_COLORS.ceiling);
      let drawn = 0;
      let ceiling = 0;
      // Half a line's width past the area on each side: the lines at 0 and 1 lie on its edges.
      const x0 = Math.floor((area.left - 2) * ratio);
      const y0 = Math.floor((area.top - 2) * ratio);
      const w = Math.ceil((area.width + 4) * ratio);
      const h = Math.ceil((area.height + 4) * ratio);
      if (ctx) {
        const px = ctx.getImageData(x0, y0, w, h).data;
        for (let i = 0; i < px.length; i += 4) {
          const off = (r: number, g: number, b: number) => Math.max(Math.abs(px[i] - r), Math.abs(px[i + 1] - g), Math.abs(px[i + 2] - b));
          if (off(br, bg, bb) > 24 && off(gr, gg, gb) > 24) drawn++;
          if (off(cr, cg, cb) < 40) ceiling++;
        }
      }
      return { samples: app.plot.series.samples.slice(), drawnPixels: drawn, ceilingPixels: ceiling, pixels: w * h };
    },
    version: () => bridge.current?.version ?? -1,
    /** The selected balloon, its card, the force arrows drawn, the motion plot, the caption, the teaching scenes. */
    physics: () => app.physics.snapshot(),
    /** The air's sources, the fans and vents drawn, the fan tool, "show air"'s motes. */
    air: () => app.air.snapshot(),
    sceneJson: () => JSON.stringify(app.scene),
    messages: () => messages.shown.slice(),
    camera: () => ({ position: camera.position.toArray(), target: controls.center().toArray() }),
    /** World centre of balloon i's root sphere, at its size now (what a click should aim at). */
    balloonCenter(i: number): [number, number, number] | null {
      const p = bridge.curr;
      const root = app.info?.trees[bridge.models[i] ?? 0]?.[0];
      const at = i * POSE_STRIDE;
      if (!root || p.length < at + POSE_STRIDE) return null;
      const q = new THREE.Quaternion(p[at + 3], p[at + 4], p[at + 5], p[at + 6]);
      const scale = bridge.scales[i] ?? 1;
      const c = new THREE.Vector3(...root.center)
        .multiplyScalar(scale)
        .applyQuaternion(q)
        .add(new THREE.Vector3(p[at], p[at + 1], p[at + 2]));
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
    /**
     * Renders once (without the balloons or the ribbons when asked) and counts the
     * pixels of hue within `hueDegrees` of `rgb`'s and saturated (over 0.35,
     * not dark): a lit, shaded surface of that colour. In the client
     * rectangle `region` (CSS pixels; the whole view when left out).
     */
    colorPixels(
      rgb: [number, number, number],
      hueDegrees: number,
      region?: { left: number; top: number; right: number; bottom: number },
      hide: { balloons?: boolean; ribbons?: boolean } = {},
    ) {
      const hue = (r: number, g: number, b: number) => {
        const max = Math.max(r, g, b);
        const d = max - Math.min(r, g, b);
        if (d === 0) return 0;
        const h = max === r ? ((g - b) / d) % 6 : max === g ? (b - r) / d + 2 : (r - g) / d + 4;
        return (h * 60 + 360) % 360;
      };
      const target = hue(...rgb);
      const balloons = world.balloons;
      const ribbons = world.ribbons?.mesh;
      const ribbonsShown = ribbons?.visible ?? false;
      if (hide.balloons && balloons) balloons.setVisible(false);
      if (hide.ribbons && ribbons) ribbons.visible = false;
      renderer.render(scene, camera);
      if (hide.balloons && balloons) balloons.setVisible(true);
      if (ribbons) ribbons.visible = ribbonsShown;
      const gl = renderer.getContext();
      const w = gl.drawingBufferWidth;
      const h = gl.drawingBufferHeight;
      const rect = renderer.domElement.getBoundingClientRect();
      const sx = w / rect.width;
      const sy = h / rect.height;
      const r = region ?? { left: rect.left, top: rect.top, right: rect.right, bottom: rect.bottom };
      const x0 = Math.max(0, Math.floor((r.left - rect.left) * sx));
      const x1 = Math.min(w, Math.ceil((r.right - rect.left) * sx));
      // WebGL's rows start at the bottom.
      const y0 = Math.max(0, Math.floor(h - (r.bottom - rect.top) * sy));
      const y1 = Math.min(h, Math.ceil(h - (r.top - rect.top) * sy));
      if (x1 <= x0 || y1 <= y0) return { matching: 0, pixels: 0 };
      const px = new Uint8Array((x1 - x0) * (y1 - y0) * 4);
      gl.readPixels(x0, y0, x1 - x0, y1 - y0, gl.RGBA, gl.UNSIGNED_BYTE, px);
      let matching = 0;
      for (let i = 0; i < px.length; i += 4) {
        const max = Math.max(px[i], px[i + 1], px[i + 2]);
        const min = Math.min(px[i], px[i + 1], px[i + 2]);
        if (max < 40 || (max - min) / max < 0.35) continue;
        const off = Math.abs(hue(px[i], px[i + 1], px[i + 2]) - target);
        if (Math.min(off, 360 - off) <= hueDegrees) matching++;
      }
      return { matching, pixels: px.length / 4 };
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
