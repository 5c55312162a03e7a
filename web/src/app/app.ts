// The app: the stage and the world drawn on it, the physics worker, the
// controls, the HUD, the panel, the toolbar, the layout and the share link,
// and what each of them does to the others. The parts live in render/, sim/, ui/ and scene/; this class
// only holds them and routes their events.

import { createStage, type Stage } from "../render/stage";
import { WorldView } from "../render/worldView";
import { saveScreenshot } from "../render/screenshot";
import { SimBridge } from "../sim/bridge";
import { MAX_THREADS, requestedPool, requestedThreads } from "../sim/threadPool";
import type { EngineStats } from "../sim/engine";
import type { WorldInfo } from "../sim/protocol";
import { Controls } from "../ui/controls";
import { Hud } from "../ui/hud";
import { FloatPlot } from "../ui/floatPlot";
import { Messages } from "../ui/messages";
import { Panel, type PanelActions } from "../ui/panel";
import type { KeyAction } from "../ui/input";
import { applyParams, paramsFromScene, type PanelParams } from "../scene/sceneParams";
import type { Scene } from "../scene/sceneSchema";
import { ShareLink } from "./shareLink";
import { PhysicsView } from "./physicsView";
import { AirView } from "./airView";
import { FrameMeter } from "./frameMeter";
import { PhotoMode } from "../render/photo/photoMode";
import { photoHost } from "./photoHost";
import { ClipRecorder } from "../ui/recorder";
import { downloadBlob, timestampName } from "../render/photo/download";
import { PageLayout } from "../ui/layout";
import { Toolbar } from "../ui/toolbar";
import { CrowdGovernor, costText, drawingBudget, type DrawingBudget } from "../render/drawingBudget";
import type { PageElements } from "./page";

/** Most balloons the panel's slider offers (the engine's capacity may be higher). */
const PANEL_MAX_BALLOONS = 5000;

/** Height of the room's highest point, m: the walls, plus the apex under a pyramid ceiling. */
function roomTop(p: PanelParams): number {
  return p.wallHeight + (p.ceiling === "pyramid" ? p.apexHeight : 0);
}

export class App {
  readonly stage: Stage;
  readonly world: WorldView;
  readonly hud: Hud;
  readonly messages: Messages;
  readonly link: ShareLink;
  readonly bridge: SimBridge;
  readonly controls: Controls;
  /** Where the balloons float against simulated time. */
  readonly plot: FloatPlot;
  /** The selected balloon, force arrows, motion plots, teaching scenes. */
  readonly physics: PhysicsView;
  /** Fans, vents, "show air" and the fan tool. */
  readonly air: AirView;
  panel: Panel | null = null;
  readonly photo: PhotoMode;
  readonly recorder: ClipRecorder;
  /** The layout by the window's size (compact on a phone or a tablet). */
  readonly layout: PageLayout;
  /** The buttons under the room: add, pause, step, photo, record. */
  readonly toolbar: Toolbar;
  /** What a frame may cost on this device; `governor` lowers its crowd count while frames are slow. */
  readonly budget: DrawingBudget;
  private readonly governor: CrowdGovernor | null;
  /** When the first frame with balloons was drawn, ms on the page's clock (null before). */
  firstDrawAt: number | null = null;
  /** When the app started (its bundle run, its stage built), the engine's first world and the balloon model were ready, and the first render call took how long, ms (where the first draw's time goes). */
  readonly startup = { stageMs: 0, startAt: null as number | null, engineAt: null as number | null, assetsAt: null as number | null, firstRenderMs: null as number | null };
  /** The engine's description of the world shown (null until the first is ready). */
  info: WorldInfo | null = null;
  /** The scene shown, as the engine read it (every default written out); its live settings as the engine last took them. */
  scene: Scene = {};
  /** The worker's last stats and its steps per second. */
  lastStats: { stats: EngineStats; stepsPerSecond: number } | null = null;
  /** Frames drawn with balloons, and main-thread ms spent in renderer.render over them (measurements). */
  readonly frames = { drawn: 0, renderMs: 0 };
  private drawingHeldNow = false;
  /** The main thread's work and render call per frame (measurements). */
  readonly frameMeter = new FrameMeter();
  private firstWorld = true;
  private lastFrameTime = performance.now();

  /**
   * Measurements only: frames do nothing, so that the page sends the GPU
   * nothing to draw or composite. Headless Chromium draws through
   * SwiftShader on the CPU, which would take the cores that a timed physics
   * window is measuring.
   */
  get drawingHeld(): boolean {
    return this.drawingHeldNow;
  }

  set drawingHeld(held: boolean) {
    this.drawingHeldNow = held;
    this.tellDrawing();
  }

  /** The worker's pool spins or sleeps by whether frames are drawn (`?spin=auto`): not while held or while the tab is hidden. */
  private tellDrawing(): void {
    this.bridge.setDrawing(!this.drawingHeldNow && !document.hidden);
  }

  constructor(private readonly page: PageElements) {
    this.budget = drawingBudget({
      coarsePointer: window.matchMedia("(pointer: coarse)").matches,
      screenShortSide: Math.min(window.screen.width, window.screen.height),
    });
    this.governor = this.budget.lighter ? new CrowdGovernor(this.budget.crowdAbove) : null;
    this.layout = new PageLayout(document.body);
    this.messages = new Messages(page.message, page.fatal);
    this.link = new ShareLink(this.messages);
    // The engine first: its worker fetches, compiles and builds the world while this thread builds the stage.
    this.bridge = new SimBridge({
      ready: (info) => this.worldReady(info),
      frame: () => {
        this.panel?.setPaused(this.bridge.paused);
        this.toolbar.setPaused(this.bridge.paused);
        this.world.takeFrame(this.bridge);
      },
      stats: (stats, stepsPerSecond) => {
        this.lastStats = { stats, stepsPerSecond };
        this.hud.setStats(stats, stepsPerSecond);
      },
      census: (sample) => this.plot.push(sample),
      error: (message, fatal) => this.engineError(message, fatal),
      scene: (json) => {
        // A live setting or an air tool's change taken: the scene (and its link) say so.
        this.scene = JSON.parse(json) as Scene;
        this.link.set(JSON.stringify(this.scene));
      },
      airField: (field) => this.air.takeField(field),
    });
    const { threads, error: threadsError } = requestedThreads(location.search, navigator.hardwareConcurrency);
    this.bridge.init(new URL("wasm/up_wasm.wasm", document.baseURI).href, this.link.takeInitial(), threads, requestedPool(location.search));
    // A hidden tab draws no frames (the browser stops them), a page opened in one among them.
    document.addEventListener("visibilitychange", () => this.tellDrawing());
    if (document.hidden) this.tellDrawing();
    const stageStart = performance.now();
    this.stage = createStage(page.app, this.budget);
    this.startup.stageMs = performance.now() - stageStart;
    // Hidden until its first frame with balloons: a browser that composites in software (SwiftShader,
    // the phone's stand-in) reads a shown WebGL canvas back at each frame, which holds this thread
    // until the GPU has done all it was given (the environment map's passes take seconds there),
    // and the model and the engine's worker would wait behind it (docs/perf-log.md).
    this.stage.renderer.domElement.style.visibility = "hidden";
    this.world = new WorldView(this.stage.scene);
    this.hud = new Hud(page.hud);
    this.hud.setCost(costText(this.budget));
    if (threadsError) this.messages.error(threadsError);
    this.plot = new FloatPlot(document.body);
    this.physics = new PhysicsView(this.stage.scene, document.body, this.bridge, this.stage.camera);
    this.controls = new Controls(this.stage.camera, this.stage.renderer.domElement, this.bridge, {
      select: (index) => this.physics.select(index),
      action: (a) => this.keyAction(a),
      placement: (on) => {
        this.hud.setMode(on ? "Placement mode: tap or click the floor to add a balloon · add (CTRL) to go back" : "");
        this.toolbar.setPlacement(on);
      },
      touched: () => this.layout.markHelpRead(),
    });
    this.air = new AirView(this.stage.scene, this.stage.renderer.domElement, this.bridge, (x, y) => this.controls.floorPoint(x, y), (hint) => this.hud.setMode(hint));
    const band = document.getElementById("bottom-band") ?? document.body;
    this.toolbar = new Toolbar(band, {
      add: () => this.controls.setPlacement(!this.controls.placement),
      togglePause: () => this.togglePause(),
      step: () => this.bridge.singleStep(),
      photo: () => this.photo.toggle(),
      record: () => this.recorder.toggle(),
    });
    // In the compact layout the help line is a button: a tap says it has been read, and the float plot takes its place.
    document.getElementById("help")?.addEventListener("click", () => this.layout.markHelpRead());
    this.photo = new PhotoMode(photoHost(this));
    this.recorder = new ClipRecorder(
      this.stage.renderer.domElement,
      (on) => {
        this.panel?.setRecording(on);
        this.toolbar.setRecording(on);
      },
      (m) => this.messages.error(m),
    );
  }

  /**
   * Reads the balloon model (preloaded by index.html) and starts drawing;
   * the engine has been starting since the constructor. The first frame
   * waits for the model: drawing a frame can hold this thread until the GPU
   * has drawn it (for seconds on a software rasterizer), and the model's
   * few milliseconds of reading would wait behind it.
   */
  start(): void {
    this.startup.startAt = performance.now();
    const assets = this.world
      .loadAssets(new URL("assets/", document.baseURI).href)
      .then(() => {
        this.startup.assetsAt = performance.now();
        this.world.balloons?.setCrowdAbove(this.budget.crowdAbove);
      })
      .catch((e: Error) => this.messages.fatal("The balloon model failed to load", e.message));
    window.addEventListener("resize", () => {
      this.stage.resize();
      this.layout.resize();
    });
    // A window that becomes compact folds the panel; one that widens unfolds it.
    this.layout.onChange((layout, changed) => {
      if (changed && this.panel) this.panel.gui.open(!layout.compact);
    });
    void assets.then(() => requestAnimationFrame((now) => this.frame(now)));
  }

  /** Whether the engine and the balloon model are in and balloons have been drawn. */
  get ready(): boolean {
    return !!this.info && !!this.world.assets && this.frames.drawn > 2;
  }

  private worldReady(info: WorldInfo): void {
    this.startup.engineAt ??= performance.now();
    this.info = info;
    this.plot.clear();
    this.link.pending = false;
    // The engine's own JSON of a `Scene`.
    this.scene = JSON.parse(info.sceneJson) as Scene;
    const params = paramsFromScene(this.scene);
    const box = { halfWidth: params.width / 2, halfDepth: params.depth / 2, top: roomTop(params) };
    const roomChanged = this.world.setWorld(info);
    if (roomChanged) this.stage.fitToRoom(box.halfWidth, box.halfDepth, box.top);
    this.controls.setWorld(box, info.trees, this.firstWorld || roomChanged);
    this.air.worldReady(info);
    this.firstWorld = false;
    if (!this.panel) {
      this.panel = new Panel(params, this.scene, info.constants, this.panelActions, Math.min(PANEL_MAX_BALLOONS, info.capacity));
      const assets = new URL("assets/", document.baseURI).href;
      this.air.addPanel(this.panel.gui, info.constants);
      this.physics.addMenu(this.panel.gui, assets, () => this.messages.clear()).catch((e: Error) => this.messages.error(`The teaching scenes failed to load: ${e.message}`));
      // Threads only where memory can be shared; a new count restarts the engine on the scene shown.
      if (info.isolated) this.panel.addThreads(info.threads, Math.max(info.threads, Math.min(MAX_THREADS, navigator.hardwareConcurrency || 1)), (n) => this.bridge.restart(JSON.stringify(this.scene), n));
      // On a phone or a tablet the panel starts folded behind its title, a shared scene's page too.
      if (this.layout.layout.compact) this.panel.gui.close();
    } else this.panel.set(params, this.scene);
    this.hud.setThreads(info.threads, info.isolated);
    // A teaching scene's address is the scene the engine read from its file.
    if (this.physics.worldReady(info, this.scene)) this.link.set(info.sceneJson);
    this.page.loading.hidden = true;
  }

  private engineError(message: string, fatal: boolean): void {
    this.page.loading.hidden = true;
    if (fatal) this.messages.fatal("The physics engine failed to load", message);
    else if (this.link.pending) this.messages.error(`The shared scene could not be loaded: ${message}. Showing the default scene instead.`);
    else this.messages.error(message);
    if (this.link.pending) {
      this.link.pending = false;
      this.link.set(null);
    }
  }

  private togglePause(): void {
    if (this.controls.placement) return;
    const bridge = this.bridge;
    bridge.setPaused(!bridge.paused);
    this.panel?.setPaused(bridge.paused);
    this.hud.setMode(bridge.paused ? "Paused · play (space) resumes, step (N) steps" : "");
  }

  /** Debug view on or off; contacts come from the worker only while it is on. */
  private setDebug(on: boolean): void {
    this.world.setDebug(on, this.bridge.contacts);
    this.bridge.setDebug(on);
  }

  private screenshot(): void {
    if (this.photo.active) this.photo.save();
    else saveScreenshot(this.stage.renderer, this.stage.scene, this.stage.camera);
  }

  private keyAction(a: KeyAction): void {
    if (a.kind === "togglePause") this.togglePause();
    else if (a.kind === "singleStep") this.bridge.singleStep();
    else if (a.kind === "toggleDebug") {
      this.setDebug(!this.world.debug.visible);
      this.panel?.setDebugTrees(this.world.debug.visible);
    } else if (a.kind === "screenshot") this.screenshot();
    else if (a.kind === "deselect") this.physics.select(-1);
    else if (a.kind === "photo") this.photo.toggle();
    else if (a.kind === "record") this.recorder.toggle();
  }

  private readonly panelActions: PanelActions = {
    change: (params) => {
      const json = JSON.stringify(applyParams(this.scene, params));
      // The engine is the scene's only validator.
      void this.bridge.validate(json).then((error) => {
        if (error) {
          this.messages.error(`This scene is not valid: ${error}`);
          this.panel?.set(paramsFromScene(this.scene), this.scene);
          return;
        }
        this.messages.clear();
        this.bridge.load(json);
        this.link.set(json);
      });
    },
    // The running world takes it; the engine's scene comes back (`scene` above).
    live: (setting) => this.bridge.live(setting),
    reset: () => {
      this.messages.clear();
      this.bridge.load(null);
      this.link.set(null);
    },
    togglePause: () => this.togglePause(),
    step: () => this.bridge.singleStep(),
    timeLapse: (rate) => this.bridge.setRate(rate),
    debugTrees: (on) => this.setDebug(on),
    finish: (finish) => this.world.balloons?.setFinishOverride(finish),
    screenshot: () => this.screenshot(),
    share: () => this.link.share(JSON.stringify(this.scene), () => this.hud.setMode("Link copied to the clipboard")),
    photo: () => this.photo.toggle(),
    savePhoto: () => this.photo.save(),
    record: () => this.recorder.toggle(),
    exportGltf: () => void this.exportGltf(),
  };

  /** Downloads the frames of the last 10 simulated seconds as an animated glTF binary, for Blender. */
  private async exportGltf(): Promise<void> {
    try {
      const glb = await this.bridge.exportGltf();
      downloadBlob(new Blob([glb], { type: "model/gltf-binary" }), timestampName("up", "glb"));
    } catch (e) {
      this.messages.error(`The glTF export failed: ${e instanceof Error ? e.message : String(e)}`);
    }
  }

  /** One animation frame: controls, the world from the newest physics frame, the HUD, the render. */
  private frame(now: number): void {
    if (this.drawingHeld) {
      this.lastFrameTime = now;
      requestAnimationFrame((t) => this.frame(t));
      return;
    }
    const workStart = performance.now();
    const intervalMs = now - this.lastFrameTime;
    const dt = Math.min(0.1, intervalMs / 1000);
    this.lastFrameTime = now;
    // In photo mode the camera stays where the photo was taken.
    if (!this.photo.active) this.controls.update(dt);
    const withBalloons = this.world.update(this.bridge, performance.timeOrigin + now);
    const current = this.bridge.current;
    if (withBalloons && current) {
      this.hud.setCount(current.count);
      this.judgeCost(intervalMs, current.count);
    }
    this.layout.setSelected(!!this.bridge.forces?.card);
    if (current) this.hud.setClock(current);
    this.hud.frame(now);
    this.plot.draw();
    this.physics.update(this.world.assets, this.bridge.alpha(performance.timeOrigin + now));
    this.air.update(dt);
    const { renderer, scene, camera } = this.stage;
    const renderStart = performance.now();
    // Nothing is drawn on the hidden canvas: frames drawn there would queue up on a software GPU unseen.
    if (!withBalloons && this.firstDrawAt === null) {
      requestAnimationFrame((t) => this.frame(t));
      return;
    }
    if (this.photo.active) this.photo.render();
    else renderer.render(scene, camera);
    const renderEnd = performance.now();
    this.frames.renderMs += renderEnd - renderStart;
    this.frameMeter.record(renderStart - workStart, renderEnd - renderStart);
    if (withBalloons) {
      this.frames.drawn++;
      if (this.firstDrawAt === null) {
        this.stage.renderer.domElement.style.visibility = "";
        this.firstDrawAt = performance.now();
        this.startup.firstRenderMs = renderEnd - renderStart;
      }
    }
    requestAnimationFrame((t) => this.frame(t));
  }

  /** On a lighter budget: slow frames with the full balloon mesh move the crowd mesh's count down (drawingBudget.ts). */
  private judgeCost(intervalMs: number, count: number): void {
    if (!this.governor || this.photo.active) return;
    const lowered = this.governor.frame(intervalMs, count);
    if (lowered === null) return;
    this.budget.crowdAbove = lowered;
    this.world.balloons?.setCrowdAbove(lowered);
    this.hud.setCost(costText(this.budget));
  }
}
