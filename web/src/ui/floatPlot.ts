// The live plot: the share of the balloons at the ceiling, hovering and on the
// floor against simulated time, drawn on a 2D canvas of its own. Three
// polylines and two labels need no charting library (none is a dependency),
// and a canvas of ours redraws without touching the DOM per sample.

/** Where the balloons were at simulated time `t`, s: each share of all balloons, 0–1. */
export interface FloatSample {
  t: number;
  ceiling: number;
  hovering: number;
  floor: number;
}

/** Most samples kept; beyond, every other one is dropped (the plot is a few hundred pixels wide). */
export const MAX_SAMPLES = 1024;

/** The samples of the world shown, thinned as they grow. */
export class FloatSeries {
  readonly samples: FloatSample[] = [];

  /** Adds a sample; one earlier than the last means a new world, which starts the series afresh. */
  push(sample: FloatSample): void {
    const last = this.samples[this.samples.length - 1];
    if (last && sample.t < last.t) this.samples.length = 0;
    this.samples.push(sample);
    if (this.samples.length > MAX_SAMPLES) {
      // Keep the first and every other one after it, and always the newest.
      const kept = this.samples.filter((_, i) => i % 2 === 0);
      if (kept[kept.length - 1] !== sample) kept.push(sample);
      this.samples.length = 0;
      this.samples.push(...kept);
    }
  }

  clear(): void {
    this.samples.length = 0;
  }
}

/** Spans the time axis snaps to, s: a minute up to two days, then whole days. */
const SPANS = [60, 300, 900, 1800, 3600, 2 * 3600, 3 * 3600, 6 * 3600, 12 * 3600, 24 * 3600, 48 * 3600];

/** The time axis's span for samples up to `t` s: the first round span that holds it. */
export function axisSpan(t: number): number {
  for (const s of SPANS) if (t <= s) return s;
  return Math.ceil(t / 86_400) * 86_400;
}

/** The span's label: "1 min", "15 min", "2 h", "3 d". */
export function spanLabel(span: number): string {
  if (span < 3600) return `${Math.round(span / 60)} min`;
  if (span < 3 * 86_400) return `${Math.round(span / 3600)} h`;
  return `${Math.round(span / 86_400)} d`;
}

/** The plot area inside the canvas, CSS pixels. */
export interface PlotArea {
  left: number;
  top: number;
  width: number;
  height: number;
}

/** Maps (time s, share 0–1) to canvas pixels: time 0 at the left, `span` at the right, share 1 at the top. */
export function toPixel(area: PlotArea, span: number, t: number, share: number): [number, number] {
  const x = area.left + (Math.min(Math.max(t, 0), span) / span) * area.width;
  const y = area.top + (1 - Math.min(Math.max(share, 0), 1)) * area.height;
  return [x, y];
}

/** The lines' colours: warm for the ceiling (the one the plot is about), cool for hovering, grey for the floor. */
export const PLOT_COLORS = { background: "#141826", grid: "#3a4157", text: "#c8ccd8", ceiling: "#ffb020", hovering: "#4fc3f7", floor: "#9e9e9e" } as const;

const SERIES: { key: "ceiling" | "hovering" | "floor"; label: string }[] = [
  { key: "floor", label: "floor" },
  { key: "hovering", label: "hovering" },
  { key: "ceiling", label: "at the ceiling" },
];

/** The plot's canvas in the page; `draw` when the series changed. */
export class FloatPlot {
  readonly canvas: HTMLCanvasElement;
  readonly series = new FloatSeries();
  /** Where the lines go, CSS pixels: between the legend on top and the axis's words below. */
  readonly area: PlotArea;
  private dirty = true;

  constructor(
    parent: HTMLElement,
    private readonly width = 260,
    private readonly height = 120,
  ) {
    this.canvas = document.createElement("canvas");
    this.canvas.id = "float-plot";
    this.canvas.setAttribute("role", "img");
    this.canvas.setAttribute("aria-label", "share of balloons at the ceiling against simulated time");
    const ratio = Math.max(1, Math.min(3, window.devicePixelRatio || 1));
    this.canvas.width = Math.round(width * ratio);
    this.canvas.height = Math.round(height * ratio);
    this.canvas.style.width = `${width}px`;
    this.canvas.style.height = `${height}px`;
    this.area = { left: 8, top: 18, width: width - 16, height: height - 36 };
    parent.appendChild(this.canvas);
  }

  push(sample: FloatSample): void {
    this.series.push(sample);
    this.dirty = true;
  }

  clear(): void {
    this.series.clear();
    this.dirty = true;
  }

  /** Redraws when something changed since the last draw (called once per animation frame). */
  draw(): void {
    if (!this.dirty) return;
    this.dirty = false;
    const ctx = this.canvas.getContext("2d");
    if (!ctx) return;
    const ratio = this.canvas.width / this.width;
    ctx.setTransform(ratio, 0, 0, ratio, 0, 0);
    ctx.fillStyle = PLOT_COLORS.background;
    ctx.fillRect(0, 0, this.width, this.height);
    const area = this.area;
    const samples = this.series.samples;
    const last = samples[samples.length - 1];
    const span = axisSpan(last?.t ?? 0);
    ctx.strokeStyle = PLOT_COLORS.grid;
    ctx.lineWidth = 1;
    for (const share of [0, 0.5, 1]) {
      const [, y] = toPixel(area, span, 0, share);
      ctx.beginPath();
      ctx.moveTo(area.left, Math.round(y) + 0.5);
      ctx.lineTo(area.left + area.width, Math.round(y) + 0.5);
      ctx.stroke();
    }
    ctx.font = "11px system-ui, sans-serif";
    // The legend on top, each line's name in its colour; what is plotted along the bottom.
    ctx.textBaseline = "top";
    let legendX = area.left;
    for (const { key, label } of [...SERIES].reverse()) {
      ctx.fillStyle = PLOT_COLORS[key];
      ctx.fillText(label, legendX, 3);
      legendX += ctx.measureText(label).width + 12;
    }
    ctx.fillStyle = PLOT_COLORS.text;
    ctx.textBaseline = "bottom";
    ctx.fillText("0", area.left, this.height - 3);
    ctx.textAlign = "center";
    ctx.fillText("share of balloons over time", area.left + area.width / 2, this.height - 3);
    ctx.textAlign = "right";
    ctx.fillText(spanLabel(span), area.left + area.width, this.height - 3);
    ctx.textAlign = "left";
    if (samples.length === 0) return;
    for (const { key } of SERIES) {
      ctx.strokeStyle = PLOT_COLORS[key];
      ctx.lineWidth = key === "ceiling" ? 2 : 1.25;
      ctx.beginPath();
      samples.forEach((s, i) => {
        const [x, y] = toPixel(area, span, s.t, s[key]);
        if (i === 0) ctx.moveTo(x, y);
        else ctx.lineTo(x, y);
        // A lone sample still shows, as a short tick.
        if (samples.length === 1) ctx.lineTo(x + 3, y);
      });
      ctx.stroke();
    }
  }
}
