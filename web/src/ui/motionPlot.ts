// The selected balloon's motion as live plots: its height and its vertical
// speed against simulated time, the engine's terminal speed as a dashed line
// on the speed plot. A canvas of its own, like the float census's plot
// (floatPlot.ts): two polylines and a dashed line need no charting library.
// Samples go into a ring buffer every frame; the canvas is redrawn on an
// animation frame when samples came, at most a few times a second.

/** Samples kept: a minute at 60 frames a second, more than the window shows. */
export const RING_CAPACITY = 4096;
/** Most simulated seconds shown; older samples scroll off to the left. */
export const WINDOW_S = 30;
/** Shortest time between two redraws, ms. */
export const REDRAW_MS = 250;

/** A fixed-size ring of (time, height, vertical speed) samples: no allocation per sample. */
export class SampleRing {
  private readonly data: Float64Array;
  private start = 0;
  length = 0;

  constructor(readonly capacity = RING_CAPACITY) {
    this.data = new Float64Array(capacity * 3);
  }

  /** Adds a sample, overwriting the oldest when full. */
  push(t: number, height: number, speed: number): void {
    const slot = (this.start + this.length) % this.capacity;
    this.data[slot * 3] = t;
    this.data[slot * 3 + 1] = height;
    this.data[slot * 3 + 2] = speed;
    if (this.length < this.capacity) this.length++;
    else this.start = (this.start + 1) % this.capacity;
  }

  clear(): void {
    this.start = 0;
    this.length = 0;
  }

  /** Sample `i`, oldest first: field 0 time, 1 height, 2 vertical speed. */
  get(i: number, field: 0 | 1 | 2): number {
    return this.data[((this.start + i) % this.capacity) * 3 + field];
  }

  /** The newest sample's time, or NaN when empty. */
  lastTime(): number {
    return this.length === 0 ? NaN : this.get(this.length - 1, 0);
  }
}

/** The time axis: the last `window` seconds, or from the first sample while there are fewer. */
export function timeRange(first: number, last: number, window = WINDOW_S): [number, number] {
  if (!Number.isFinite(first) || !Number.isFinite(last)) return [0, window];
  const start = Math.max(first, last - window);
  return [start, Math.max(start + window, last)];
}

/**
 * A value axis holding every value in `[min, max]` with a margin, at least
 * `minSpan` wide, its ends on multiples of a round step (1, 2 or 5 × 10ⁿ).
 */
export function valueRange(min: number, max: number, minSpan: number): { low: number; high: number; step: number } {
  if (!Number.isFinite(min) || !Number.isFinite(max)) {
    min = 0;
    max = 0;
  }
  const mid = (min + max) / 2;
  const span = Math.max(max - min, minSpan) * 1.1;
  const raw = span / 4;
  const power = 10 ** Math.floor(Math.log10(raw));
  const step = [1, 2, 5, 10].map((k) => k * power).find((s) => s >= raw) ?? 10 * power;
  const low = Math.floor((mid - span / 2) / step) * step;
  const high = Math.ceil((mid + span / 2) / step) * step;
  return { low, high, step };
}

/** Min and max of field `field` over the samples at or after time `from`. */
export function extent(ring: SampleRing, field: 1 | 2, from: number): [number, number] {
  let min = Infinity;
  let max = -Infinity;
  for (let i = 0; i < ring.length; i++) {
    if (ring.get(i, 0) < from) continue;
    const v = ring.get(i, field);
    if (v < min) min = v;
    if (v > max) max = v;
  }
  return [min, max];
}

export const MOTION_COLORS = { background: "#141826", grid: "#3a4157", text: "#c8ccd8", height: "#7ee081", speed: "#4fc3f7", terminal: "#ffb020" } as const;

interface Panel {
  top: number;
  height: number;
  field: 1 | 2;
  label: string;
  color: string;
  minSpan: number;
}

/** The plots' canvas, bottom right; `draw` on every animation frame (it returns at once unless due). */
export class MotionPlot {
  readonly canvas: HTMLCanvasElement;
  readonly ring = new SampleRing();
  /** The terminal speed drawn, signed as the balloon goes (up when it lifts), m/s; NaN: none. */
  terminal = NaN;
  /** Simulated seconds shown: `WINDOW_S` in real time, that many real seconds' worth in a time-lapse. */
  window = WINDOW_S;
  private dirty = false;
  private lastDraw = -Infinity;
  private readonly panels: Panel[];
  private readonly left = 44;

  constructor(
    parent: HTMLElement,
    private readonly width = 270,
    private readonly height = 150,
  ) {
    this.canvas = document.createElement("canvas");
    this.canvas.id = "motion-plot";
    this.canvas.setAttribute("role", "img");
    this.canvas.setAttribute("aria-label", "the selected balloon's height and vertical speed against simulated time");
    const ratio = Math.max(1, Math.min(3, window.devicePixelRatio || 1));
    this.canvas.width = Math.round(width * ratio);
    this.canvas.height = Math.round(height * ratio);
    this.canvas.style.width = `${width}px`;
    this.canvas.style.height = `${height}px`;
    this.canvas.hidden = true;
    const h = (height - 52) / 2;
    this.panels = [
      { top: 16, height: h, field: 1, label: "height (m)", color: MOTION_COLORS.height, minSpan: 0.2 },
      { top: 16 + h + 18, height: h, field: 2, label: "vertical speed (m/s)", color: MOTION_COLORS.speed, minSpan: 0.2 },
    ];
    parent.appendChild(this.canvas);
  }

  /** A sample of the selected balloon at simulated time `t`; one earlier than the last starts afresh (a new world). */
  push(t: number, height: number, verticalSpeed: number, terminal: number): void {
    const last = this.ring.lastTime();
    if (t === last) return;
    if (t < last) this.ring.clear();
    this.ring.push(t, height, verticalSpeed);
    this.terminal = terminal;
    this.dirty = true;
  }

  /** Another balloon, or none: the plots start empty. */
  reset(): void {
    this.ring.clear();
    this.terminal = NaN;
    this.dirty = true;
  }

  /** Redraws when samples came and the last redraw is `REDRAW_MS` old. */
  draw(now = performance.now()): void {
    if (!this.dirty || this.canvas.hidden || now - this.lastDraw < REDRAW_MS) return;
    this.dirty = false;
    this.lastDraw = now;
    const ctx = this.canvas.getContext("2d");
    if (!ctx) return;
    const ratio = this.canvas.width / this.width;
    ctx.setTransform(ratio, 0, 0, ratio, 0, 0);
    ctx.fillStyle = MOTION_COLORS.background;
    ctx.fillRect(0, 0, this.width, this.height);
    ctx.font = "11px system-ui, sans-serif";
    const ring = this.ring;
    const [t0, t1] = timeRange(ring.length ? ring.get(0, 0) : NaN, ring.lastTime());
    const right = this.width - 8;
    const x = (t: number) => this.left + ((t - t0) / (t1 - t0)) * (right - this.left);
    for (const panel of this.panels) {
      let [min, max] = extent(ring, panel.field, t0);
      const withTerminal = panel.field === 2 && Number.isFinite(this.terminal);
      if (withTerminal) {
        min = Math.min(min, this.terminal, 0);
        max = Math.max(max, this.terminal, 0);
      }
      const range = valueRange(min, max, panel.minSpan);
      const y = (v: number) => panel.top + (1 - (v - range.low) / (range.high - range.low)) * panel.height;
      // Grid lines and their values at the axis's ends and middle.
      ctx.strokeStyle = MOTION_COLORS.grid;
      ctx.fillStyle = MOTION_COLORS.text;
      ctx.lineWidth = 1;
      ctx.textAlign = "right";
      ctx.textBaseline = "middle";
      for (const v of [range.low, (range.low + range.high) / 2, range.high]) {
        const py = Math.round(y(v)) + 0.5;
        ctx.beginPath();
        ctx.moveTo(this.left, py);
        ctx.lineTo(right, py);
        ctx.stroke();
        ctx.fillText(Number(v.toPrecision(3)).toString(), this.left - 4, py);
      }
      ctx.textAlign = "left";
      ctx.textBaseline = "bottom";
      ctx.fillStyle = panel.color;
      ctx.fillText(panel.label, this.left, panel.top - 2);
      if (withTerminal) {
        ctx.strokeStyle = MOTION_COLORS.terminal;
        ctx.setLineDash([5, 4]);
        ctx.beginPath();
        ctx.moveTo(this.left, y(this.terminal));
        ctx.lineTo(right, y(this.terminal));
        ctx.stroke();
        ctx.setLineDash([]);
        ctx.fillStyle = MOTION_COLORS.terminal;
        ctx.textAlign = "right";
        ctx.fillText(`terminal ${signedText(this.terminal)} m/s`, right, panel.top - 2);
        ctx.textAlign = "left";
      }
      ctx.strokeStyle = panel.color;
      ctx.lineWidth = 1.5;
      ctx.beginPath();
      let started = false;
      for (let i = 0; i < ring.length; i++) {
        const t = ring.get(i, 0);
        if (t < t0) continue;
        const px = x(t);
        const py = y(ring.get(i, panel.field));
        if (!started) ctx.moveTo(px, py);
        else ctx.lineTo(px, py);
        started = true;
      }
      ctx.stroke();
    }
    ctx.fillStyle = MOTION_COLORS.text;
    ctx.textBaseline = "bottom";
    ctx.textAlign = "left";
    ctx.fillText(timeText(t0), this.left, this.height - 2);
    ctx.textAlign = "right";
    ctx.fillText(timeText(t1), right, this.height - 2);
    ctx.textAlign = "center";
    ctx.fillText("simulated time", (this.left + right) / 2, this.height - 2);
    ctx.textAlign = "left";
  }

  /** Samples in the time window now (for the test hook). */
  pointsShown(): number {
    const [t0] = timeRange(this.ring.length ? this.ring.get(0, 0) : NaN, this.ring.lastTime(), this.window);
    let n = 0;
    for (let i = 0; i < this.ring.length; i++) if (this.ring.get(i, 0) >= t0) n++;
    return n;
  }
}

/** A time on the axis: seconds up to ten minutes, then minutes, then hours. */
export function timeText(t: number): string {
  if (t < 600) return `${t.toFixed(0)} s`;
  if (t < 36_000) return `${(t / 60).toFixed(0)} min`;
  return `${(t / 3600).toFixed(1)} h`;
}

function signedText(v: number): string {
  return `${v >= 0 ? "+" : "−"}${Math.abs(v).toFixed(2)}`;
}
