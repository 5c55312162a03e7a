// The worker's time-lapse: how much simulated time a tick asks of the engine
// (`Engine.advance`), how many steps it may take to keep within the frame's
// budget, and the rate the clock actually achieved. No engine here: the
// worker feeds it wall times and the engine's answers.

/** The rates the panel offers: simulated seconds per real second (1 is real time, stepped as ever). */
export const TIME_LAPSE_RATES = [1, 60, 600, 3600] as const;

/** Wall ms a tick may spend stepping in time-lapse: the rest of the 16.7 ms frame sends poses and answers input. */
export const STEP_BUDGET_MS = 12;

/** A tick longer than this, s (a tab in the background, a long GC), counts as this long: no catch-up burst. */
export const MAX_TICK_S = 0.1;

/** Over about this long, s, the achieved rate and the cost of a step are averaged. */
const SMOOTHING_S = 1;

/** What one `advance` call did, as the engine returns it. */
export interface AdvanceDone {
  /** Simulated seconds advanced (less than asked when the steps ran out). */
  seconds: number;
  steps: number;
  jumps: number;
}

export class TimeLapse {
  /** Simulated seconds per real second asked for. */
  rate = 1;
  /** Wall ms per step or jump, smoothed (the start guess is a large world's). */
  msPerStep = 1;
  private simSum = 0;
  private realSum = 0;

  /** Sets the rate asked for; the achieved rate starts afresh. */
  setRate(rate: number): void {
    if (!Number.isFinite(rate) || rate < 1) throw new RangeError(`time-lapse rate ${rate}: expected at least 1`);
    this.rate = rate;
    this.simSum = 0;
    this.realSum = 0;
  }

  /** Whether ticks go through `advance` (else they take fixed steps in real time). */
  get lapsing(): boolean {
    return this.rate > 1;
  }

  /** Simulated seconds and the most steps a tick of `realSeconds` asks of `advance`. */
  plan(realSeconds: number): { seconds: number; maxSteps: number } {
    const real = Math.min(MAX_TICK_S, Math.max(0, realSeconds));
    return { seconds: this.rate * real, maxSteps: Math.max(1, Math.floor(STEP_BUDGET_MS / this.msPerStep)) };
  }

  /** Records a tick: `done` in `wallMs` of stepping over `realSeconds` since the last tick. */
  record(done: AdvanceDone, wallMs: number, realSeconds: number): void {
    const work = done.steps + done.jumps;
    if (work > 0 && Number.isFinite(wallMs) && wallMs >= 0) {
      // Browsers coarsen performance.now(): a tick's 0 ms means "cheap", not "free".
      const perStep = Math.max(wallMs, 0.05) / work;
      const w = Math.min(1, work / 60);
      this.msPerStep += (perStep - this.msPerStep) * w;
    }
    const real = Math.min(MAX_TICK_S, Math.max(0, realSeconds));
    const keep = Math.exp(-real / SMOOTHING_S);
    this.simSum = this.simSum * keep + done.seconds;
    this.realSum = this.realSum * keep + real;
  }

  /** Simulated seconds per real second over the last second or so (0 before any tick). */
  get achieved(): number {
    return this.realSum > 0 ? this.simSum / this.realSum : 0;
  }
}

/**
 * Simulated seconds between two looks at where the balloons float (the
 * plot's samples): half a real second's worth, at least every simulated
 * second (a rise takes seconds) and at most a simulated minute apart (what
 * changes over hours needs no finer grain).
 */
export function censusInterval(rate: number): number {
  return Math.min(60, Math.max(1, rate * 0.5));
}
