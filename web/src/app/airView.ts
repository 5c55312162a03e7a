// The moving air on the page: the fans and vents drawn from the engine's
// sources (render/airSources.ts), "show air"'s motes (render/airMotes.ts),
// the air's arrow at the selected balloon (render/airArrow.ts), the fan
// tool (ui/fanTool.ts) and the panel's "Air" folder (ui/airPanel.ts). It
// routes their events to the engine as air commands through the bridge;
// everything drawn comes back from the engine in the frames.

import type * as THREE from "three";
import { AirSourcesView } from "../render/airSources";
import { AirMotes } from "../render/airMotes";
import { AirArrow } from "../render/airArrow";
import { readSources, type AirField, type AirSource, type Vec3 } from "../sim/airLayout";
import { roomBox } from "../sim/airSampler";
import type { SimBridge } from "../sim/bridge";
import type { Constants } from "../sim/engine";
import { findForceRow } from "../sim/forcesFrame";
import type { WorldInfo } from "../sim/protocol";
import { AirPanel } from "../ui/airPanel";
import { FanTool } from "../ui/fanTool";
import { fanAt, fanNear } from "../ui/fanPlacement";
import { FAN_SPEED_M_S } from "../ui/fanPlacement";

/** What the HUD says while the fan tool is on. */
export const FAN_TOOL_HINT = "Fan tool: click the floor to place a fan, drag to aim it; click a fan to pick it · right-drag turns the view";

export class AirView {
  readonly sources: AirSourcesView;
  readonly motes = new AirMotes();
  readonly arrow = new AirArrow();
  readonly tool: FanTool;
  panel: AirPanel | null = null;
  /** The jet index of the fan the panel's speed and "remove" are for; -1: none. */
  selected = -1;
  /** The speed and sweep of fans placed next. */
  private speed = FAN_SPEED_M_S;
  private sweeps = false;
  /** Set when a fan was asked for: it becomes the selected one once it arrives (the jets it will follow). */
  private awaitedFan = -1;
  private parsed: AirSource[] = [];
  private parsedFrom: Float32Array | null = null;
  /** The frame the arrow shows. */
  private arrowFrame: unknown = null;

  constructor(
    scene: THREE.Scene,
    canvas: HTMLElement,
    private readonly bridge: SimBridge,
    floorPoint: (clientX: number, clientY: number) => [number, number, number] | null,
    private readonly hint: (text: string) => void,
    capacity = 32,
  ) {
    this.sources = new AirSourcesView(capacity);
    scene.add(this.sources.group, this.motes.group, this.arrow.arrow);
    this.tool = new FanTool(canvas, floorPoint, {
      place: (at, aim) => this.place(at, aim),
      pick: (at) => {
        const fan = fanNear(at, this.parsed);
        if (fan < 0) return false;
        this.select(fan);
        return true;
      },
    });
  }

  /** Adds the panel's "Air" folder. */
  addPanel(gui: ConstructorParameters<typeof AirPanel>[0], constants: Pick<Constants, "air">): void {
    this.panel = new AirPanel(gui, constants, {
      fanTool: (on) => this.setTool(on),
      fanSpeed: (speed) => {
        this.speed = speed;
        if (this.selected >= 0) this.bridge.air({ command: "set_fan_speed", fan: this.selected, speed_m_s: speed });
      },
      sweep: (on) => (this.sweeps = on),
      removeFan: () => {
        if (this.selected < 0) return;
        this.bridge.air({ command: "remove_fan", fan: this.selected });
        this.select(-1);
      },
      openDoor: (seconds) => this.bridge.air({ command: "open_door", seconds }),
      showAir: (on) => this.setShowAir(on),
    });
  }

  setTool(on: boolean): void {
    this.tool.setOn(on);
    this.panel?.setFanTool(on);
    this.hint(on ? FAN_TOOL_HINT : "");
  }

  setShowAir(on: boolean): void {
    this.motes.setShown(on);
    this.bridge.setShowAir(on);
  }

  /** A new world: its floor and centre, no fan selected, the motes start afresh (and the worker is told again whether to sample). */
  worldReady(info: WorldInfo): void {
    const { min, max } = roomBox(info.room.vertices);
    this.sources.setFloor(min[1]);
    this.tool.floorY = min[1];
    this.tool.center = [(min[0] + max[0]) / 2, (min[2] + max[2]) / 2];
    this.motes.reset();
    this.select(-1);
    this.awaitedFan = -1;
    this.bridge.setShowAir(this.motes.shown);
  }

  /** The newest field from the worker. */
  takeField(field: AirField): void {
    this.motes.setField(field);
  }

  private place(at: [number, number], aim: Vec3): void {
    this.awaitedFan = this.parsed.filter((s) => s.kind !== "draught").length;
    this.bridge.air({ command: "add_fan", fan: fanAt(at, this.tool.floorY, aim, this.speed, this.sweeps) });
  }

  private select(fan: number): void {
    this.selected = fan;
    const source = fan >= 0 ? this.parsed.find((s) => s.jet === fan) : undefined;
    if (source) this.speed = source.fullSpeed;
    this.panel?.setSelected(fan >= 0 ? fan : null, source ? source.fullSpeed : null);
  }

  /** The sources of the newest frame. */
  private current(): AirSource[] {
    const rows = this.bridge.airSources;
    if (rows !== this.parsedFrom) {
      this.parsedFrom = rows;
      this.parsed = readSources(rows);
      const jets = this.parsed.filter((s) => s.kind !== "draught").length;
      if (this.awaitedFan >= 0 && jets > this.awaitedFan) {
        const fan = this.awaitedFan;
        this.awaitedFan = -1;
        this.select(fan);
      } else if (this.selected >= jets) this.select(-1);
    }
    return this.parsed;
  }

  /** One animation frame of `dt` seconds: the sources, the motes (still while paused), the arrow. */
  update(dt: number): void {
    const sources = this.current();
    const moving = this.bridge.paused ? 0 : dt;
    this.sources.update(sources, moving, this.tool.preview(), this.selected);
    this.motes.update(sources, moving);
    const frame = this.bridge.current;
    if (frame !== this.arrowFrame) {
      this.arrowFrame = frame;
      const forces = this.bridge.forces;
      const card = forces?.card ?? null;
      const row = forces && card ? findForceRow(forces.rows, card.index) : null;
      this.arrow.set(row ? row.centerOfMass : null, card ? card.air_velocity_m_s : null);
    }
  }

  /** What the tests read: the sources, what is drawn of them, the tool, the motes. */
  snapshot() {
    return {
      sources: this.current().map((s) => ({ ...s })),
      fansDrawn: this.sources.fans,
      ventsDrawn: this.sources.vents,
      drawCalls: this.sources.drawCalls(),
      selected: this.selected,
      tool: this.tool.on,
      showAir: this.motes.shown,
      motes: this.motes.motes.count,
      motesVisible: this.motes.visibleCount,
      arrowShown: this.arrow.arrow.visible,
    };
  }
}
