// A fixed window of physics, measured in the worker: the engine steps one
// step at a time from where it is, and each step's time is read twice — the
// engine's own timer (its stats' "total", averaged since the last read: one
// step here) and the worker's clock around the call. The state hash after the
// window is the same on any number of threads, so runs on different thread
// counts can be checked against each other at the same step.

import type { EngineStats } from "./engine";

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
  for (let i = 0; i < steps; i++) {
    const t0 = clock();
    engine.step(1);
    wallMs.push(clock() - t0);
    const stats = engine.stats();
    engineMs.push(total(stats));
    addStages(stageSums, stats);
  }
  const last = engine.stats();
  return {
    steps,
    engineMs,
    wallMs,
    stageMeanMs: stageSums.map(([name, sum]) => [name, sum / steps]),
    stateHash: hashHex(engine.stateHash()),
    bodies: last.bodies,
    awake: last.awake,
    contacts: last.contacts,
  };
}
