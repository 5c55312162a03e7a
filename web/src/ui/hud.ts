// The heads-up display: balloon count, the simulated clock (time since the
// start, the room's temperature, the time-lapse rate asked and achieved),
// frames per second, and milliseconds per physics step by stage; what the
// page does to draw for less on a small device; and, for the compact layout
// (layout.ts), all of it in one line that a tap opens into the whole.

import type { EngineStats } from "../sim/engine";
import { NOT_ISOLATED_TEXT } from "../sim/threadPool";
import { formatAchievedRate, formatCelsius, formatClock, formatRate } from "./clock";

/** What the clock line shows. */
export interface ClockReading {
  /** Simulated seconds since the start. */
  simTime: number;
  airTemperatureC: number;
  rate: number;
  achievedRate: number;
}

/** The clock line's text: "Clock 1:02:03 · 20.0 °C · ×3 600 (now ×2 900)". */
export function clockText(c: ClockReading): string {
  const pace = c.rate === 1 ? formatRate(1) : `${formatRate(c.rate)} (now ${formatAchievedRate(c.achievedRate)})`;
  return `Clock ${formatClock(c.simTime)} · ${formatCelsius(c.airTemperatureC)} · ${pace}`;
}

/** What the compact layout's one line reads. */
export interface CompactReading {
  count: number;
  simTime: number;
  rate: number;
  /** Frames per second, NaN before the first second. */
  fps: number;
  /** Whether the page draws for less (the cost line says how). */
  lighter: boolean;
}

/** The compact HUD's line: "50 balloons · 0:01:23 · ×60 · 58 fps · lighter ▾" (the rate only in a time-lapse). */
export function compactLine(r: CompactReading): string {
  const parts = [`${r.count} balloon${r.count === 1 ? "" : "s"}`, formatClock(r.simTime)];
  if (r.rate !== 1) parts.push(formatRate(r.rate));
  parts.push(Number.isFinite(r.fps) ? `${r.fps.toFixed(0)} fps` : "– fps");
  if (r.lighter) parts.push("lighter");
  return `${parts.join(" · ")} ▾`;
}

/** The HUD's threads line. */
export function threadsText(threads: number, isolated: boolean): string {
  return isolated ? `Threads: ${threads}` : NOT_ISOLATED_TEXT;
}

export class Hud {
  private readonly count: HTMLElement;
  private readonly clock: HTMLElement;
  private readonly fps: HTMLElement;
  private readonly physics: HTMLElement;
  private readonly stages: HTMLElement;
  private readonly mode: HTMLElement;
  private readonly threads: HTMLElement;
  private readonly photo: HTMLElement;
  private readonly cost: HTMLElement;
  private readonly line: HTMLElement;
  private frames = 0;
  private since = performance.now();
  private lastCount = -1;
  private readonly reading: CompactReading = { count: 0, simTime: 0, rate: 1, fps: NaN, lighter: false };

  constructor(private readonly root: HTMLElement) {
    root.innerHTML = `
      <div id="hud-line"></div>
      <div id="hud-count" class="hud-big">Balloons: 0</div>
      <div id="hud-clock">Clock 0:00:00</div>
      <div id="hud-fps">FPS: –</div>
      <div id="hud-physics">Physics: – ms/step</div>
      <div id="hud-threads"></div>
      <div id="hud-stages"></div>
      <div id="hud-mode"></div>
      <div id="hud-cost" hidden></div>
      <div id="hud-photo" hidden></div>`;
    this.count = root.querySelector("#hud-count")!;
    this.clock = root.querySelector("#hud-clock")!;
    this.fps = root.querySelector("#hud-fps")!;
    this.physics = root.querySelector("#hud-physics")!;
    this.stages = root.querySelector("#hud-stages")!;
    this.mode = root.querySelector("#hud-mode")!;
    this.threads = root.querySelector("#hud-threads")!;
    this.photo = root.querySelector("#hud-photo")!;
    this.cost = root.querySelector("#hud-cost")!;
    this.line = root.querySelector("#hud-line")!;
    // In the compact layout only the line shows (style.css); a tap on it opens the whole HUD, another folds it.
    root.setAttribute("aria-expanded", "false");
    root.addEventListener("click", () => this.setExpanded(!this.expanded));
    this.updateLine();
  }

  get expanded(): boolean {
    return this.root.classList.contains("expanded");
  }

  setExpanded(on: boolean): void {
    this.root.classList.toggle("expanded", on);
    this.root.setAttribute("aria-expanded", String(on));
  }

  private updateLine(): void {
    const text = compactLine(this.reading);
    if (this.line.textContent !== text) this.line.textContent = text;
  }

  /** Call once per drawn frame. */
  frame(now: number): void {
    this.frames++;
    const elapsed = now - this.since;
    if (elapsed >= 500) {
      this.reading.fps = (this.frames * 1000) / elapsed;
      this.fps.textContent = `FPS: ${this.reading.fps.toFixed(0)}`;
      this.frames = 0;
      this.since = now;
      this.updateLine();
    }
  }

  setCount(n: number): void {
    if (n === this.lastCount) return;
    this.lastCount = n;
    this.count.textContent = `Balloons: ${n}`;
    this.reading.count = n;
    this.updateLine();
  }

  setClock(reading: ClockReading): void {
    const text = clockText(reading);
    if (this.clock.textContent !== text) this.clock.textContent = text;
    this.reading.simTime = reading.simTime;
    this.reading.rate = reading.rate;
    this.updateLine();
  }

  /** What the page leaves out to draw for less on this device (null: nothing); the compact line says "lighter". */
  setCost(text: string | null): void {
    this.cost.hidden = text === null;
    this.cost.textContent = text ?? "";
    this.reading.lighter = text !== null;
    this.updateLine();
  }

  setStats(stats: EngineStats, stepsPerSecond: number): void {
    const total = stats.stages.find(([name]) => name === "total")?.[1] ?? 0;
    // Two lines (style.css keeps the break): the step's cost, then what it handled.
    this.physics.textContent = `Physics: ${total.toFixed(2)} ms/step · ${stepsPerSecond.toFixed(0)} steps/s\n${stats.contacts} contacts${stats.ribbons > 0 ? ` · ${stats.ribbons} ribbons` : ""}`;
    const rows = stats.stages
      .filter(([name]) => name !== "total")
      .map(([name, ms]) => `<div><span>${name}</span><span>${ms.toFixed(2)}</span></div>`)
      .join("");
    this.stages.innerHTML = rows;
  }

  /** The threads stepping the engine, or, on a page that is not isolated, that it runs on one. */
  setThreads(threads: number, isolated: boolean): void {
    this.threads.textContent = threadsText(threads, isolated);
  }

  /** Photo mode's line: its samples so far, or null out of photo mode. */
  setPhoto(samples: number | null): void {
    this.photo.hidden = samples === null;
    if (samples !== null) this.photo.textContent = `Photo: ${samples} samples · any key: back to the live view`;
  }

  setMode(text: string): void {
    this.mode.textContent = text;
    this.mode.style.display = text ? "block" : "none";
  }
}
