// The fan tool: while it is on, a left press on the floor starts a fan
// there, dragging aims it (level, toward the pointer), releasing places it;
// a click near a fan's stand picks that fan instead (the panel's speed and
// "remove" are for it). Presses elsewhere (off the floor, other buttons) go
// to the camera as usual. Its listeners run before the camera's and the
// balloons' (capture phase on the canvas) and keep the presses they take.
// The decisions are pure (fanPlacement.ts).

import type { Vec3 } from "../sim/airLayout";
import { FAN_DIAMETER_M, FAN_OUTLET_HEIGHT_M, defaultFanAim, fanAimFromDrag } from "./fanPlacement";
import { pointerKind, tapSlop } from "./gestures";

export interface FanToolEvents {
  /** A fan to add: its floor point (x, z) and its aim. */
  place(at: [number, number], aim: Vec3): void;
  /** A click near a fan picked it (its jet index). */
  pick(at: [number, number]): boolean;
}

/** What the tool draws while a fan is being aimed. */
export interface FanPreview {
  outlet: Vec3;
  aim: Vec3;
  diameter: number;
}

export class FanTool {
  on = false;
  /** The floor the fan stands on, m. */
  floorY = 0;
  /** The room's centre on the floor (x, z): a clicked fan faces it. */
  center: [number, number] = [0, 0];
  private press: { id: number; x: number; y: number; at: [number, number]; end: [number, number] } | null = null;

  constructor(
    private readonly canvas: HTMLElement,
    /** The floor point (x, y, z) under a client point, inside the room, or null. */
    private readonly floorPoint: (clientX: number, clientY: number) => [number, number, number] | null,
    private readonly events: FanToolEvents,
  ) {
    const capture = { capture: true };
    canvas.addEventListener("pointerdown", (e) => this.down(e), capture);
    canvas.addEventListener("pointermove", (e) => this.move(e), capture);
    canvas.addEventListener("pointerup", (e) => this.up(e), capture);
    canvas.addEventListener("pointercancel", (e) => this.cancel(e), capture);
  }

  setOn(on: boolean): void {
    this.on = on;
    this.press = null;
  }

  /** The fan being aimed, or null. */
  preview(): FanPreview | null {
    const p = this.press;
    if (!p) return null;
    return { outlet: [p.at[0], this.floorY + FAN_OUTLET_HEIGHT_M, p.at[1]], aim: this.aim(p.at, p.end), diameter: FAN_DIAMETER_M };
  }

  private aim(at: [number, number], end: [number, number]): Vec3 {
    return fanAimFromDrag(at, end) ?? defaultFanAim(at, this.center);
  }

  private down(e: PointerEvent): void {
    if (!this.on || e.button !== 0 || this.press) return;
    const hit = this.floorPoint(e.clientX, e.clientY);
    if (!hit) return;
    e.stopImmediatePropagation();
    const at: [number, number] = [hit[0], hit[2]];
    this.press = { id: e.pointerId, x: e.clientX, y: e.clientY, at, end: at };
    this.canvas.setPointerCapture?.(e.pointerId);
  }

  private move(e: PointerEvent): void {
    const p = this.press;
    if (!p || e.pointerId !== p.id) return;
    e.stopImmediatePropagation();
    const hit = this.floorPoint(e.clientX, e.clientY);
    if (hit) p.end = [hit[0], hit[2]];
  }

  private up(e: PointerEvent): void {
    const p = this.press;
    if (!p || e.pointerId !== p.id) return;
    e.stopImmediatePropagation();
    this.press = null;
    const click = Math.hypot(e.clientX - p.x, e.clientY - p.y) <= tapSlop(pointerKind(e.pointerType));
    if (click && this.events.pick(p.at)) return;
    this.events.place(p.at, click ? defaultFanAim(p.at, this.center) : this.aim(p.at, p.end));
  }

  private cancel(e: PointerEvent): void {
    if (this.press && e.pointerId === this.press.id) {
      e.stopImmediatePropagation();
      this.press = null;
    }
  }
}
