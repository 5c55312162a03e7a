// The main thread's own cost per animation frame, measured in the page: the
// work (controls, poses to instance matrices, ribbons, HUD, plot) and the
// renderer.render call, each frame's in a ring of the most recent frames.
// `make measure` reads it through the tests' hook; a visitor's page records
// two numbers a frame and nothing else.

/** Frames kept: a minute at 60 fps, enough for a measuring window. */
export const FRAME_METER_CAPACITY = 3600;

export interface FrameSummary {
  /** Frames summarised. */
  n: number;
  /** ms of frame work (everything but the render call): median, p95, mean, max. */
  work: { median: number; p95: number; mean: number; max: number } | null;
  /** ms in renderer.render (the draw calls' submission; the GPU's time is not in it). */
  render: { median: number; p95: number; mean: number; max: number } | null;
}

/** The sample at quantile q of ascending `sorted` (nearest rank, as the benchmarks take it). */
export function quantile(sorted: ArrayLike<number>, q: number): number {
  const n = sorted.length;
  const rank = Math.ceil(Math.min(Math.max(q, 0), 1) * n);
  return sorted[Math.min(Math.max(rank, 1), n) - 1];
}

function describe(values: Float64Array): FrameSummary["work"] {
  if (values.length === 0) return null;
  const sorted = values.slice().sort();
  let sum = 0;
  for (const v of sorted) sum += v;
  return { median: quantile(sorted, 0.5), p95: quantile(sorted, 0.95), mean: sum / sorted.length, max: sorted[sorted.length - 1] };
}

export class FrameMeter {
  private readonly work: Float64Array;
  private readonly render: Float64Array;
  /** Frames recorded since the last reset (the ring holds the newest `capacity`). */
  private recorded = 0;

  constructor(readonly capacity = FRAME_METER_CAPACITY) {
    this.work = new Float64Array(capacity);
    this.render = new Float64Array(capacity);
  }

  /** One frame: ms of work before the render call, and ms inside it. */
  record(workMs: number, renderMs: number): void {
    const i = this.recorded % this.capacity;
    this.work[i] = workMs;
    this.render[i] = renderMs;
    this.recorded++;
  }

  /** Forgets every frame (a measuring window starts). */
  reset(): void {
    this.recorded = 0;
  }

  /** The frames in the ring, oldest first. */
  samples(): { work: Float64Array; render: Float64Array } {
    const n = Math.min(this.recorded, this.capacity);
    const start = this.recorded > this.capacity ? this.recorded % this.capacity : 0;
    const order = (a: Float64Array) => {
      const out = new Float64Array(n);
      for (let k = 0; k < n; k++) out[k] = a[(start + k) % this.capacity];
      return out;
    };
    return { work: order(this.work), render: order(this.render) };
  }

  summary(): FrameSummary {
    const { work, render } = this.samples();
    return { n: work.length, work: describe(work), render: describe(render) };
  }
}
