// The heads-up display: balloon count, the simulated clock (time since the
// start, the room's temperature, the time-lapse rate asked and achieved),
// frames per second, and milliseconds per physics step by stage.

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
  private frames = 0;
  private since = performance.now();
  private lastCount = -1;

  constructor(root: HTMLElement) {
    root.innerHTML = `
      <div id="hud-count" class="hud-big">Balloons: 0</div>
      <div id="hud-clock">Clock 0:00:00</div>
      <div id="hud-fps">FPS: –</div>
      <div id="hud-physics">Physics: – ms/step</div>
      <div id="hud-threads"></div>
      <div id="hud-stages"></div>
      <div id="hud-mode"></div>
      <div id="hud-photo" hidden></div>`;
    this.count = root.querySelector("#hud-count")!;
    this.clock = root.querySelector("#hud-clock")!;
    this.fps = root.querySelector("#hud-fps")!;
    this.physics = root.querySelector("#hud-physics")!;
    this.stages = root.querySelector("#hud-stages")!;
    this.mode = root.querySelector("#hud-mode")!;
    this.threads = root.querySelector("#hud-threads")!;
    this.photo = root.querySelector("#hud-photo")!;
  }

  /** Call once per drawn frame. */
  frame(now: number): void {
    this.frames++;
    const elapsed = now - this.since;
    if (elapsed >= 500) {
      this.fps.textContent = `FPS: ${((this.frames * 1000) / elapsed).toFixed(0)}`;
      this.frames = 0;
      this.since = now;
    }
  }

  setCount(n: number): void {
    if (n === this.lastCount) return;
    this.lastCount = n;
    this.count.textContent = `Balloons: ${n}`;
  }

  setClock(reading: ClockReading): void {
    const text = clockText(reading);
    if (this.clock.textContent !== text) this.clock.textContent = text;
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
