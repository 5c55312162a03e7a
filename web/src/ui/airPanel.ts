// The panel's "Air" folder: the fan tool's toggle, the speed of the
// selected (or last placed) fan, whether new fans sweep, removing the
// selected fan, the door draught, and "show air". Each control is one
// action; the commands they lead to are the engine's (`AirCommand`).

import type GUI from "lil-gui";
import type { Constants } from "../sim/engine";
import { FAN_SPEED_M_S } from "./fanPlacement";

/** How long the door stays open, s. */
export const DOOR_OPEN_S = 10;
/** The speed slider's top, m/s: a household fan's range, finer to pick than the engine's 30. */
export const FAN_SLIDER_MAX_M_S = 10;

export interface AirPanelActions {
  /** The fan tool on or off. */
  fanTool(on: boolean): void;
  /** The selected fan's speed (and that of fans placed next), m/s. */
  fanSpeed(speed: number): void;
  /** Whether fans placed next sweep side to side. */
  sweep(on: boolean): void;
  removeFan(): void;
  openDoor(seconds: number): void;
  showAir(on: boolean): void;
}

export class AirPanel {
  readonly folder: GUI;
  readonly values = { fanTool: false, speed: FAN_SPEED_M_S, sweep: false, showAir: false };
  private readonly speedControl: ReturnType<GUI["add"]>;
  private readonly removeControl: ReturnType<GUI["add"]>;

  constructor(gui: GUI, constants: Pick<Constants, "air">, actions: AirPanelActions) {
    const folder = (this.folder = gui.addFolder("Air"));
    const tag = <T extends { domElement: HTMLElement }>(c: T, key: string): T => {
      c.domElement.dataset.key = key;
      return c;
    };
    const v = this.values;
    tag(folder.add(v, "fanTool"), "fanTool")
      .name("place a fan (click the floor, drag to aim)")
      .onChange((on: boolean) => actions.fanTool(on));
    this.speedControl = tag(folder.add(v, "speed", 0, Math.min(FAN_SLIDER_MAX_M_S, constants.air.max_fan_speed_m_s), 0.1), "fanSpeed")
      .name("fan speed (m/s)")
      .onFinishChange((speed: number) => actions.fanSpeed(speed));
    tag(folder.add(v, "sweep"), "fanSweep")
      .name("new fans sweep")
      .onChange((on: boolean) => actions.sweep(on));
    const buttons = { remove: () => actions.removeFan(), door: () => actions.openDoor(DOOR_OPEN_S) };
    this.removeControl = tag(folder.add(buttons, "remove"), "removeFan").name("remove the fan").disable();
    tag(folder.add(buttons, "door"), "door").name(`door draught (${DOOR_OPEN_S} s)`);
    tag(folder.add(v, "showAir"), "showAir")
      .name("show air")
      .onChange((on: boolean) => actions.showAir(on));
  }

  /** The fan the speed is for (its number from 1; null: none), and its speed. */
  setSelected(fan: number | null, speed: number | null): void {
    this.speedControl.name(fan === null ? "fan speed (m/s)" : `fan ${fan + 1} speed (m/s)`);
    if (speed !== null) this.values.speed = speed;
    this.speedControl.updateDisplay();
    this.removeControl.enable(fan !== null);
  }

  /** Shows the tool as on or off (Escape or a new world may turn it off). */
  setFanTool(on: boolean): void {
    this.values.fanTool = on;
    for (const c of this.folder.controllers) c.updateDisplay();
  }
}
