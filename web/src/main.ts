// Wiring only: the stage, the physics worker, the room and balloons, the
// controls, the HUD, the panel, the scene link, and a test hook for the
// end-to-end tests (window.__up).

import "./style.css";
import * as THREE from "three";
import { createStage, hasWebGL } from "./render/stage";
import { buildRoom } from "./render/room";
import { Balloons, loadBalloonAssets, type BalloonAssets } from "./render/balloons";
import { DebugView } from "./render/debugView";
import { SimBridge } from "./sim/bridge";
import type { WorldInfo } from "./sim/protocol";
import { Controls } from "./ui/controls";
import { Hud } from "./ui/hud";
import { Messages } from "./ui/messages";
import { Panel } from "./ui/panel";
import type { KeyAction } from "./ui/input";
import { decodeSceneParam, encodeSceneHash, sceneParam } from "./scene/sceneLink";
import { applyParams, paramsFromScene, type PanelParams } from "./scene/sceneParams";

const $ = (id: string) => document.getElementById(id)!;
const messages = new Messages($("message"), $("fatal"));
const loading = $("loading");

function start(): void {
  if (!hasWebGL()) {
    loading.hidden = true;
    messages.fatal(
      "WebGL is not available",
      "UP draws the balloon room with WebGL 2, which this browser (or its graphics driver) does not provide. " +
        "Try a current Chrome, Firefox or Safari, or enable hardware acceleration.",
    );
    return;
  }
  const stage = createStage($("app"));
  const { renderer, scene, camera } = stage;
  const hud = new Hud($("hud"));
  const debug = new DebugView();
  scene.add(debug.group);

  let room: THREE.Group | null = null;
  let balloons: Balloons | null = null;
  let assets: BalloonAssets | null = null;
  let info: WorldInfo | null = null;
  let currentScene: Record<string, unknown> = {};
  let panel: Panel | null = null;
  let drawnVersion = -1;
  let firstWorld = true;
  let lastRoomKey = "";
  let linkPending = false;
  let framesDrawn = 0;
  /** The frame whose contacts the debug view shows. */
  let contactsFrame: unknown = null;
  /** Main-thread milliseconds spent in renderer.render, summed (measurements). */
  let renderMs = 0;
  let lastStats: { stats: unknown; stepsPerSecond: number } | null = null;

  // A shared link carries the scene; a malformed one is reported and the default scene shown.
  let initialJson: string | null = null;
  const param = sceneParam(location.hash);
  if (param !== null) {
    const decoded = decodeSceneParam(param);
    if (decoded.ok) {
      initialJson = decoded.json;
      linkPending = true;
    } else {
      messages.error(`${decoded.error}. Showing the default scene instead.`);
      history.replaceState(null, "", location.pathname + location.search);
    }
  }

  const setHash = (json: string | null) => {
    const url = location.pathname + location.search + (json ? encodeSceneHash(json) : "");
    history.replaceState(null, "", url);
  };

  const bridge = new SimBridge({
    ready(worldInfo) {
      info = worldInfo;
      linkPending = false;
      currentScene = JSON.parse(worldInfo.sceneJson) as Record<string, unknown>;
      const params = paramsFromScene(currentScene);
      const roomKey = worldInfo.room.vertices.join(",");
      if (roomKey !== lastRoomKey) {
        if (room) scene.remove(room);
        room = buildRoom(worldInfo.room);
        scene.add(room);
        stage.fitToRoom(params.width / 2, params.depth / 2, params.wallHeight + (params.ceiling === "pyramid" ? params.apexHeight : 0));
      }
      controls.setWorld(
        { halfWidth: params.width / 2, halfDepth: params.depth / 2, top: params.wallHeight + (params.ceiling === "pyramid" ? params.apexHeight : 0) },
        worldInfo.trees,
        firstWorld || roomKey !== lastRoomKey,
      );
      lastRoomKey = roomKey;
      firstWorld = false;
      debug.setTrees(worldInfo.trees);
      balloons?.setWorld(worldInfo.palette, worldInfo.colorNames, worldInfo.diameters);
      drawnVersion = -1;
      if (!panel) panel = new Panel(params, panelActions, Math.min(5000, worldInfo.capacity));
      else panel.set(params);
      loading.hidden = true;
    },
    frame() {
      panel?.setPaused(bridge.paused);
    },
    stats(stats, stepsPerSecond) {
      lastStats = { stats, stepsPerSecond };
      hud.setStats(stats, stepsPerSecond);
    },
    error(message, fatal) {
      loading.hidden = true;
      if (fatal) messages.fatal("The physics engine failed to load", message);
      else if (linkPending) messages.error(`The shared scene could not be loaded: ${message}. Showing the default scene instead.`);
      else messages.error(message);
      if (linkPending) {
        linkPending = false;
        setHash(null);
      }
    },
  });

  const controls = new Controls(camera, renderer.domElement, bridge, {
    action: (a) => keyAction(a),
    placement(on) {
      hud.setMode(on ? "Placement mode: click the floor to add a balloon · CTRL to go back" : "");
    },
  });

  function togglePause(): void {
    if (controls.placement) return;
    bridge.setPaused(!bridge.paused);
    panel?.setPaused(bridge.paused);
    hud.setMode(bridge.paused ? "Paused · space to resume, N to step" : "");
  }

  function screenshot(): void {
    renderer.render(scene, camera);
    renderer.domElement.toBlob((blob) => {
      if (!blob) return;
      const a = document.createElement("a");
      a.href = URL.createObjectURL(blob);
      a.download = `up-${new Date().toISOString().replace(/[:.]/g, "-")}.png`;
      a.click();
      setTimeout(() => URL.revokeObjectURL(a.href), 1000);
    }, "image/png");
  }

  /** Debug view on or off; contacts come from the worker only while it is on. */
  function setDebug(on: boolean): void {
    debug.visible = on;
    bridge.setDebug(on);
    contactsFrame = null;
    if (!on) debug.setContacts(bridge.contacts, 0);
  }

  function keyAction(a: KeyAction): void {
    if (a.kind === "togglePause") togglePause();
    else if (a.kind === "singleStep") bridge.singleStep();
    else if (a.kind === "toggleDebug") {
      setDebug(!debug.visible);
      panel?.setDebugTrees(debug.visible);
    } else if (a.kind === "screenshot") screenshot();
  }

  const panelActions = {
    change(params: PanelParams) {
      const json = JSON.stringify(applyParams(currentScene, params));
      // The engine is the scene's only validator.
      void bridge.validate(json).then((error) => {
        if (error) {
          messages.error(`This scene is not valid: ${error}`);
          panel?.set(paramsFromScene(currentScene));
          return;
        }
        messages.clear();
        bridge.load(json);
        setHash(json);
      });
    },
    reset() {
      messages.clear();
      bridge.load(null);
      setHash(null);
    },
    togglePause,
    step: () => bridge.singleStep(),
    debugTrees(on: boolean) {
      setDebug(on);
    },
    screenshot,
    share() {
      setHash(JSON.stringify(currentScene));
      const url = location.href;
      navigator.clipboard?.writeText(url).then(
        () => hud.setMode("Link copied to the clipboard"),
        () => window.prompt("Copy this link to share the scene:", url),
      ) ?? window.prompt("Copy this link to share the scene:", url);
    },
  };

  loadBalloonAssets(new URL("assets/", document.baseURI).href)
    .then((a) => {
      assets = a;
      balloons = new Balloons(a);
      scene.add(balloons.group);
      if (info) balloons.setWorld(info.palette, info.colorNames, info.diameters);
    })
    .catch((e: Error) => messages.fatal("The balloon model failed to load", e.message));

  bridge.init(new URL("wasm/up_wasm.wasm", document.baseURI).href, initialJson);

  window.addEventListener("resize", () => stage.resize());

  let last = performance.now();
  function loop(now: number): void {
    const dt = Math.min(0.1, (now - last) / 1000);
    last = now;
    controls.update(dt);
    const f = bridge.current;
    if (f && balloons) {
      if (f.version !== drawnVersion && bridge.colors.length === f.count) {
        balloons.setBodies(bridge.colors, bridge.models);
        drawnVersion = f.version;
      }
      balloons.update(bridge.prev, bridge.curr, f.count, bridge.alpha(performance.timeOrigin + now));
      if (debug.visible) {
        debug.update(bridge.curr, 0, f.count, bridge.models);
        if (contactsFrame !== f) {
          debug.setContacts(bridge.contacts, f.contactCount);
          contactsFrame = f;
        }
      }
      hud.setCount(f.count);
    }
    hud.frame(now);
    const renderStart = performance.now();
    renderer.render(scene, camera);
    renderMs += performance.now() - renderStart;
    if (f && balloons) framesDrawn++;
    requestAnimationFrame(loop);
  }
  requestAnimationFrame(loop);

  // Test hook for the end-to-end tests: reads state, never drives the app
  // except through the same paths as the user (pause is the space key's path).
  const hook = {
    ready: () => !!info && !!assets && framesDrawn > 2,
    balloonCount: () => bridge.current?.count ?? 0,
    poses: () => Array.from(bridge.curr),
    paused: () => bridge.paused,
    /** Frames drawn with balloons, and main-thread ms spent in renderer.render over them. */
    frames: () => ({ drawn: framesDrawn, renderMs }),
    /** The worker's last stats (stage ms per step, counts) and its steps per second. */
    stats: () => lastStats,
    debugView: () => debug.visible,
    /** Contacts the debug view draws now, and how many the current frame carried. */
    contacts: () => ({ drawn: debug.visible ? debug.contactCount : 0, inFrame: bridge.current?.contactCount ?? 0, total: bridge.current?.contactTotal ?? 0 }),
    placement: () => controls.placement,
    steps: () => bridge.current?.steps ?? 0,
    version: () => bridge.current?.version ?? -1,
    sceneJson: () => JSON.stringify(currentScene),
    messages: () => messages.shown.slice(),
    camera: () => ({ position: camera.position.toArray(), target: controls.center().toArray() }),
    /** World centre of balloon i's root sphere (what a click should aim at). */
    balloonCenter(i: number) {
      const p = bridge.curr;
      const root = info?.trees[bridge.models[i] ?? 0]?.[0];
      if (!root || p.length < (i + 1) * 7) return null;
      const q = new THREE.Quaternion(p[i * 7 + 3], p[i * 7 + 4], p[i * 7 + 5], p[i * 7 + 6]);
      const c = new THREE.Vector3(...root.center).applyQuaternion(q).add(new THREE.Vector3(p[i * 7], p[i * 7 + 1], p[i * 7 + 2]));
      return c.toArray();
    },
    /** Client pixel coordinates of a world point. */
    project(x: number, y: number, z: number) {
      const v = new THREE.Vector3(x, y, z).project(camera);
      const rect = renderer.domElement.getBoundingClientRect();
      return { x: rect.left + ((v.x + 1) / 2) * rect.width, y: rect.top + ((1 - v.y) / 2) * rect.height };
    },
    /** Renders once and measures the picture: how varied, how much saturated colour. */
    pixelStats(hideBalloons = false) {
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
  (window as unknown as { __up: typeof hook }).__up = hook;
}

start();
