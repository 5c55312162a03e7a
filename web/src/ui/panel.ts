// The lil-gui panel: the scene's parameters (a change rebuilds the world
// from the edited scene), the live settings (a change is one `LiveSetting`
// the engine applies to the running world: `LIVE_LINES`), reset, pause /
// single step, the time-lapse, the debug view, a screenshot and the share link.

import GUI from "lil-gui";
import type { PanelParams } from "../scene/sceneParams";
import { filledScene, type Scene } from "../scene/sceneSchema";
import { TIME_LAPSE_RATES } from "../sim/timeLapse";
import { formatRate } from "./clock";
import type { Constants, Finish, LiveSetting } from "../sim/engine";

/** The finish menu: every latex balloon drawn in one finish, or each group in its scene's. */
export const FINISH_OPTIONS: Record<string, Finish | "scene"> = { "as the scene says": "scene", latex: "latex", pearl: "pearl", "foil (chrome)": "foil" };

/** The time-lapse menu: each rate's name ("real time", "×60", …) to its value. */
export const TIME_LAPSE_OPTIONS: Record<string, number> = Object.fromEntries(TIME_LAPSE_RATES.map((r) => [formatRate(r), r]));

/** A live control's name: `control` of a `LiveSetting`. */
export type LiveControl = LiveSetting["control"];

/** A panel line for a live setting: where it sits, its label, and how it reads the scene. */
export interface LiveLine<C extends LiveControl = LiveControl> {
  control: C;
  folder: "Balloons" | "Physics" | "Room";
  name: string;
  /** Slider step. */
  step: number;
  /** Largest value the slider offers, when narrower than the engine's range (the usual values, finer to pick). */
  sliderMax?: number;
  /** The setting's value in `scene` (a missing key read as the engine reads it). */
  read(scene: Scene): number;
}

/**
 * The live settings, one line each. A new live control is a line here and
 * its `LiveSetting` variant in crates/up-wasm/src/live.rs: its range comes
 * from the engine (`constants.live`).
 */
export const LIVE_LINES: LiveLine[] = [
  { control: "ribbon_length", folder: "Balloons", name: "ribbon length (m, 0: none)", step: 0.05, sliderMax: 4, read: (s) => s.balloons?.[0]?.ribbon?.length_m ?? 0 },
  { control: "gravity", folder: "Room", name: "gravity (m/s², Moon 1.62)", step: 0.01, read: (s) => -filledScene(s).sim.gravity[1] },
];

/** The message a live line sends for `value`. */
export function liveSetting<C extends LiveControl>(control: C, value: number): Extract<LiveSetting, { control: C }> {
  return { control, value } as Extract<LiveSetting, { control: C }>;
}

/** The engine's range for `control` (`constants.live`), clamped to the line's slider. */
export function sliderRange(line: LiveLine, constants: Constants): { min: number; max: number } {
  const range = constants.live.find((r) => r.control === line.control);
  if (!range) throw new Error(`the engine has no live setting "${line.control}"`);
  return { min: range.min, max: Math.min(range.max, line.sliderMax ?? range.max) };
}

export interface PanelActions {
  /** A scene parameter changed (on finish: release of a slider, Enter in a box). */
  change(params: PanelParams): void;
  /** A live setting changed: the running world takes it. */
  live(setting: LiveSetting): void;
  reset(): void;
  togglePause(): void;
  step(): void;
  /** Time-lapse: simulated seconds per real second (1: real time). */
  timeLapse(rate: number): void;
  debugTrees(on: boolean): void;
  /** Draws every latex balloon in `finish`; null: as the scene says (looks only). */
  finish(finish: Finish | null): void;
  screenshot(): void;
  share(): void;
  /** Photo mode on or off (P). */
  photo(): void;
  /** Saves the photo as a PNG. */
  savePhoto(): void;
  /** Starts or stops recording a clip (R). */
  record(): void;
  /** Downloads the last 10 s of the run as an animated glTF binary (.glb). */
  exportGltf(): void;
}

export class Panel {
  readonly gui: GUI;
  private readonly params: PanelParams;
  /** The live lines' values, by control. */
  private readonly liveValues: Record<string, number> = {};
  private readonly view = { trees: false, timeLapse: 1, finish: "scene" as Finish | "scene" };
  private readonly pauseButton: ReturnType<GUI["add"]>;
  private readonly sim: GUI;
  private readonly buttons = {
    pause: () => this.actions.togglePause(),
    step: () => this.actions.step(),
    reset: () => this.actions.reset(),
    screenshot: () => this.actions.screenshot(),
    share: () => this.actions.share(),
    photo: () => this.actions.photo(),
    savePhoto: () => this.actions.savePhoto(),
    record: () => this.actions.record(),
    exportGltf: () => this.actions.exportGltf(),
  };
  private readonly photoButton: ReturnType<GUI["add"]>;
  private readonly saveButton: ReturnType<GUI["add"]>;
  private readonly recordButton: ReturnType<GUI["add"]>;

  constructor(
    initial: PanelParams,
    scene: Scene,
    constants: Constants,
    private readonly actions: PanelActions,
    maxBalloons: number,
  ) {
    this.params = { ...initial };
    for (const line of LIVE_LINES) this.liveValues[line.control] = line.read(scene);
    this.gui = new GUI({ title: "UP — scene" });
    const p = this.params;
    const changed = () => actions.change({ ...p });
    // Stable handles for the end-to-end tests: data-key="<parameter>".
    const tag = <T extends { domElement: HTMLElement }>(c: T, key: string): T => {
      c.domElement.dataset.key = key;
      return c;
    };

    const balloons = this.gui.addFolder("Balloons");
    tag(balloons.add(p, "count", 0, maxBalloons, 1), "count").name("balloons").onFinishChange(changed);
    balloons.add(p, "sizeIn", 5, 36, 0.5).name("size (inches)").onFinishChange(changed);
    balloons.add(p, "helium").name("helium (else air)").onFinishChange(changed);
    tag(balloons.add(this.view, "finish", FINISH_OPTIONS), "finish").onChange((f: Finish | "scene") => actions.finish(f === "scene" ? null : f));

    const physics = this.gui.addFolder("Physics");
    physics.add(p, "drag", 0, 3, 0.01).name("drag coefficient").onFinishChange(changed);
    physics.add(p, "restitution", 0, 1, 0.01).onFinishChange(changed);
    physics.add(p, "friction", 0, 2, 0.01).onFinishChange(changed);
    physics.add(p, "substeps", 1, 16, 1).onFinishChange(changed);

    const room = this.gui.addFolder("Room");
    room.add(p, "width", 1, 40, 0.1).name("width (m)").onFinishChange(changed);
    room.add(p, "depth", 1, 40, 0.1).name("depth (m)").onFinishChange(changed);
    room.add(p, "wallHeight", 1, 20, 0.1).name("wall height (m)").onFinishChange(changed);
    room.add(p, "ceiling", ["pyramid", "flat"]).onFinishChange(changed);
    room.add(p, "apexHeight", 0.1, 10, 0.1).name("apex height (m)").onFinishChange(changed);

    const folders = { Balloons: balloons, Physics: physics, Room: room };
    for (const line of LIVE_LINES) {
      const { min, max } = sliderRange(line, constants);
      tag(folders[line.folder].add(this.liveValues, line.control, min, max, line.step), line.control)
        .name(line.name)
        .onFinishChange((value: number) => actions.live(liveSetting(line.control, value)));
    }

    const sim = (this.sim = this.gui.addFolder("Simulation"));
    this.pauseButton = sim.add(this.buttons, "pause").name("pause (space)");
    sim.add(this.buttons, "step").name("single step (N)");
    tag(sim.add(this.view, "timeLapse", TIME_LAPSE_OPTIONS), "timeLapse")
      .name("time-lapse")
      .onChange((rate: number) => actions.timeLapse(Number(rate)));
    sim.add(this.buttons, "reset").name("reset scene");
    sim.add(this.view, "trees").name("sphere trees (D)").onChange((on: boolean) => actions.debugTrees(on));
    sim.add(this.buttons, "screenshot").name("screenshot (S)");
    sim.add(this.buttons, "share").name("copy share link");

    const media = this.gui.addFolder("Photo and clip");
    this.photoButton = tag(media.add(this.buttons, "photo"), "photo").name("photo (P)");
    this.saveButton = tag(media.add(this.buttons, "savePhoto"), "savePhoto").name("save photo (PNG)").disable();
    this.recordButton = tag(media.add(this.buttons, "record"), "record").name("record (R)");
    tag(media.add(this.buttons, "exportGltf"), "exportGltf").name("Export last 10 s (.glb)");
  }

  setPhoto(on: boolean): void {
    this.photoButton.name(on ? "back to the live view (P)" : "photo (P)");
    this.saveButton.enable(on);
  }

  setRecording(on: boolean): void {
    this.recordButton.name(on ? "stop recording (R)" : "record (R)");
  }

  /** Shows `params` and `scene`'s live settings (after a reset or a loaded link) without firing changes. */
  set(params: PanelParams, scene: Scene): void {
    Object.assign(this.params, params);
    for (const line of LIVE_LINES) this.liveValues[line.control] = line.read(scene);
    for (const c of this.gui.controllersRecursive()) c.updateDisplay();
  }

  setPaused(paused: boolean): void {
    this.pauseButton.name(paused ? "resume (space)" : "pause (space)");
  }

  /** The thread count (1 to `max`): `change` when one is picked. */
  addThreads(threads: number, max: number, change: (threads: number) => void): void {
    const view = { threads };
    const c = this.sim.add(view, "threads", 1, max, 1).name("threads (restarts)").onFinishChange((n: number) => change(Math.round(n)));
    c.domElement.dataset.key = "threads";
  }

  setDebugTrees(on: boolean): void {
    this.view.trees = on;
    for (const c of this.gui.controllersRecursive()) c.updateDisplay();
  }
}
