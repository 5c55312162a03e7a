// A fixed window of physics, measured in the worker: the engine steps one
// step at a time from where it is, and each step's time is read twice — the
// engine's own timer (its stats' "total", averaged since the last read: one
// step here) and the worker's clock around the call. The state hash after the
// window is the same on any number of threads, so runs on different thread
// counts can be checked against each other at the same step.

import type { EngineStats, StageThreadTimes } from "./engine";

/** The most steps one measuring request may take (the worker answers nothing else meanwhile). */
export const MAX_MEASURED_STEPS = 20000;

export interface StepsMeasured {
  steps: number;
  /** The engine's ms per step ("total" of its stage timers), one per step. */
  engineMs: number[];
  /** The worker's ms around each step call (the engine's time and the call's). */
  wallMs: number[];
  /** Each of the engine's stages (broadphase, …, "total" last): its mean ms per step over the window. */
  stageMeanMs: [string, number][];
  /**
   * Each thread's busy, barrier and idle ms per step in each stage over the
   * window (the step's thread first, "total" last), and the barriers and
   * passes each crossed: empty unless the engine timed its threads.
   */
  threadStages: StageThreadTimes[];
  /** The engine's state hash after the window: 16 hex digits, as the `up` CLI prints it. */
  stateHash: string;
  /** Bodies, awake bodies and contacts after the window. */
  bodies: number;
  awake: number;
  contacts: number;
}

/** What the meter needs of the engine (sim/engine.ts's Engine has it). */
export interface SteppedEngine {
  step(n?: number): void;
  stats(): EngineStats;
  stateHash(): bigint;
}

/** A u64 state hash as the `up` CLI prints it. */
export function hashHex(hash: bigint): string {
  return BigInt.asUintN(64, hash).toString(16).padStart(16, "0");
}

function total(stats: EngineStats): number {
  const entry = stats.stages.find(([name]) => name === "total");
  if (!entry) throw new Error("the engine's stats have no \"total\" stage");
  return entry[1];
}

/** Adds one step's stage times to `sums` (named as the engine names them, in its order). */
function addStages(sums: [string, number][], stats: EngineStats): void {
  if (sums.length === 0) sums.push(...stats.stages.map(([name]): [string, number] => [name, 0]));
  for (const [name, ms] of stats.stages) {
    const sum = sums.find(([n]) => n === name);
    if (sum) sum[1] += ms;
  }
}

/** Adds one step's per-thread figures to `sums` (by stage name; the threads' lists grow to the most seen). */
function addThreads(sums: StageThreadTimes[], stats: EngineStats): void {
  const add = (into: number[], from: number[]) => {
    from.forEach((ms, t) => {
      into[t] = (into[t] ?? 0) + ms;
    });
  };
  for (const row of stats.threads) {
    let sum = sums.find((s) => s.stage === row.stage);
    if (!sum) {
      sum = { stage: row.stage, wall_ms: 0, busy_ms: [], barrier_ms: [], idle_ms: [], barriers: 0, passes: 0 };
      sums.push(sum);
    }
    sum.wall_ms += row.wall_ms;
    sum.barriers += row.barriers;
    sum.passes += row.passes;
    add(sum.busy_ms, row.busy_ms);
    add(sum.barrier_ms, row.barrier_ms);
    add(sum.idle_ms, row.idle_ms);
  }
}

/** Sums over `steps` steps as means a step, "total" last. */
function threadMeans(sums: StageThreadTimes[], steps: number): StageThreadTimes[] {
  const mean = (v: number[]) => v.map((ms) => ms / steps);
  const rows = sums.map((s) => ({ ...s, wall_ms: s.wall_ms / steps, busy_ms: mean(s.busy_ms), barrier_ms: mean(s.barrier_ms), idle_ms: mean(s.idle_ms), barriers: s.barriers / steps, passes: s.passes / steps }));
  return [...rows.filter((r) => r.stage !== "total"), ...rows.filter((r) => r.stage === "total")];
}

/** Steps `engine` `steps` times, timing each step. */
export function measureSteps(engine: SteppedEngine, steps: number, clock: () => number = () => performance.now()): StepsMeasured {
  if (!Number.isInteger(steps) || steps < 1 || steps > MAX_MEASURED_STEPS) {
    throw new RangeError(`steps to measure: expected an integer from 1 to ${MAX_MEASURED_STEPS}, found ${steps}`);
  }
  // Clears the averages the page's periodic stats were gathering.
  engine.stats();
  const engineMs: number[] = [];
  const wallMs: number[] = [];
  const stageSums: [string, number][] = [];
  const threadSums: StageThreadTimes[] = [];
  for (let i = 0; i < steps; i++) {
    const t0 = clock();
    engine.step(1);
    wallMs.push(clock() - t0);
    const stats = engine.stats();
    engineMs.push(total(stats));
    addStages(stageSums, stats);
    addThreads(threadSums, stats);
  }
  const last = engine.stats();
  return {
    steps,
    engineMs,
    wallMs,
    stageMeanMs: stageSums.map(([name, sum]) => [name, sum / steps]),
    threadStages: threadMeans(threadSums, steps),
    stateHash: hashHex(engine.stateHash()),
    bodies: last.bodies,
    awake: last.awake,
    contacts: last.contacts,
  };
}
