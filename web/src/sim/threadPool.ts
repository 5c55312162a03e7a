// How many threads step the engine, and which module runs it. A cross-origin
// isolated page (SharedArrayBuffer available) runs the threaded module
// (wasm/threads/up_wasm.wasm): the engine's passes on rayon's pool, whose
// threads are Web Workers sharing the module's memory. Any other page, or one
// thread asked for, runs the single-threaded module (wasm/up_wasm.wasm). The
// results are the same, bit for bit, on any number of threads.

import { Engine, type GlueModule } from "./engine";

/** Most threads the page asks for (the `threads` address parameter's and the panel's upper bound). */
export const MAX_THREADS = 64;

/** The address parameter that sets the thread count: `?threads=4`. */
export const THREADS_PARAM = "threads";

/** What the page says, in one line, when it cannot share memory between workers. */
export const NOT_ISOLATED_TEXT = "Not cross-origin isolated: the engine runs on one thread.";

/** The threads a visitor's machine gets by default: its cores less one (the page's own thread), at least one. */
export function defaultThreads(hardwareConcurrency: number | undefined): number {
  const cores = Number.isInteger(hardwareConcurrency) && hardwareConcurrency! > 0 ? hardwareConcurrency! : 1;
  return Math.min(MAX_THREADS, Math.max(1, cores - 1));
}

/** The thread count asked for: the address's `threads` when valid, else the default; `error` says why one was refused. */
export function requestedThreads(search: string, hardwareConcurrency: number | undefined): { threads: number; error: string | null } {
  const fallback = defaultThreads(hardwareConcurrency);
  const raw = new URLSearchParams(search).get(THREADS_PARAM);
  if (raw === null) return { threads: fallback, error: null };
  const n = Number(raw);
  if (raw.trim() === "" || !Number.isInteger(n) || n < 1 || n > MAX_THREADS) {
    return {
      threads: fallback,
      error: `The address's ${THREADS_PARAM}=${raw} is not a thread count: expected an integer from 1 to ${MAX_THREADS}. Using ${fallback}.`,
    };
  }
  return { threads: n, error: null };
}

/** The module's URL for `threads` threads: the threaded build next to `singleUrl`, in `threads/`, when more than one. */
export function moduleUrl(singleUrl: string, threads: number, isolated: boolean): string {
  if (!isolated || threads <= 1) return singleUrl;
  return new URL("threads/up_wasm.wasm", singleUrl).href;
}

/**
 * How the pool runs beside the page's own threads (the physics worker, the
 * main thread, the GPU process), chosen by measurement (docs/perf-log.md)
 * and overridable by the address for measuring:
 * - `here` (`?pool=here`, the default): the physics worker is the pool's
 *   first thread and takes its share of every pass, so T threads step the
 *   world with T − 1 workers started; `beside` (`?pool=beside`): T workers
 *   started, the physics worker handing each step to them and sleeping.
 * - `spin` (`?spin=1|0|auto`): whether the pool's threads look for work
 *   through a whole step instead of sleeping between its passes
 *   (`keepThreadsAwake`). Spinning shortens every pass's hand-over, but
 *   takes cores that the page's drawing needs when the pool has them all.
 */
export interface PoolSettings {
  here: boolean;
  spin: "auto" | "on" | "off";
}

/**
 * The page's pool: the physics worker in it (never slower, one worker fewer,
 * one hand-over a step fewer), spinning through a step. `auto` was not faster
 * while the page drew on this project's 2-core machine (docs/perf-log.md,
 * 2026-12-05), so it stays a choice to measure, not the default.
 */
export const DEFAULT_POOL: PoolSettings = { here: true, spin: "on" };

/** The pool's settings the address asks for (`pool=here|beside`, `spin=auto|1|0`), the defaults otherwise. */
export function requestedPool(search: string): PoolSettings {
  const params = new URLSearchParams(search);
  const pool = params.get("pool");
  const spin = params.get("spin");
  return {
    here: pool === "here" ? true : pool === "beside" ? false : DEFAULT_POOL.here,
    spin: spin === "1" ? "on" : spin === "0" ? "off" : spin === "auto" ? "auto" : DEFAULT_POOL.spin,
  };
}

/**
 * Whether the pool's `threads` threads keep looking for work through a step:
 * as `settings.spin` says, and for `auto` unless the page draws while the
 * pool takes every core but one (`cores` − 1 leaves one to the main thread
 * and the GPU process, which a visitor's GPU barely needs and SwiftShader
 * needs whole). A thread that spins while another needs its core holds back
 * the block that thread runs, and every thread then waits at the barrier.
 */
export function keepThreadsAwake(settings: PoolSettings, threads: number, cores: number | undefined, drawing: boolean): boolean {
  if (settings.spin !== "auto") return settings.spin === "on";
  const spare = Number.isInteger(cores) && cores! > 0 ? cores! - threads : 0;
  return !drawing || spare >= 1;
}

/** The threaded module's glue: the single-threaded one's exports and its pool's. */
export interface ThreadedGlue {
  /** wasm-bindgen-rayon: fills rayon's pool with `threads` Web Workers sharing the module's memory. */
  initThreadPool(threads: number): Promise<void>;
  /** rayon's pool of `threads` (at least 2) with the calling thread its first, and `threads` − 1 Web Workers. */
  initThreadPoolHere(threads: number): Promise<void>;
  /** Whether a step keeps the pool's threads looking for work through it (on until told otherwise). */
  set_keep_threads_awake(on: boolean): void;
  /** Threads in the pool, once `initThreadPool` has resolved. */
  thread_count(): number;
}

/** An engine and the threads that step it. */
export interface StartedEngine {
  engine: Engine;
  threads: number;
  isolated: boolean;
  /** The threaded module's pool switch (`keepThreadsAwake`), or null on one thread. */
  setKeepAwake: ((on: boolean) => void) | null;
}

/**
 * Instantiates the module for `threads` threads from its `bytes` and `glue`
 * (`moduleUrl`'s), and, when threaded, starts its pool as `settings` say
 * before any step.
 */
export async function startEngine(
  glue: GlueModule,
  bytes: BufferSource,
  threads: number,
  isolated: boolean,
  settings: PoolSettings = DEFAULT_POOL,
): Promise<StartedEngine> {
  const engine = Engine.load(glue, bytes);
  if (!isolated || threads <= 1) return { engine, threads: 1, isolated, setKeepAwake: null };
  const pool = glue as unknown as ThreadedGlue;
  if (settings.here) await pool.initThreadPoolHere(threads);
  else await pool.initThreadPool(threads);
  pool.set_keep_threads_awake(keepThreadsAwake(settings, threads, globalThis.navigator?.hardwareConcurrency, true));
  return { engine, threads: pool.thread_count(), isolated, setKeepAwake: (on) => pool.set_keep_threads_awake(on) };
}
