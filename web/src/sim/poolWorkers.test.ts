// The pool's worker starter (crates/up-wasm/src/pool_workers.js) with the
// browser's Worker, fetch and blob URLs stood in for: each start makes the
// builder's workers, and a second start (a fresh instance after a trap) lets
// the first pool's workers go.

import { afterAll, beforeAll, describe, expect, it } from "vitest";

/** A worker that answers its init message as pool_workers.js's workers do. */
class FakeWorker extends EventTarget {
  static made: FakeWorker[] = [];
  terminated = false;
  init: unknown = null;
  constructor(readonly url: string) {
    super();
    FakeWorker.made.push(this);
  }
  postMessage(data: unknown): void {
    this.init = data;
    queueMicrotask(() => this.dispatchEvent(new MessageEvent("message", { data: { type: "up_pool_worker_ready" } })));
  }
  terminate(): void {
    this.terminated = true;
  }
}

interface FakeBuilder {
  built: number;
  numThreads(): number;
  receiver(): number;
  mainJS(): string;
  build(): void;
}

function builder(threads: number): FakeBuilder {
  return {
    built: 0,
    numThreads: () => threads - 1,
    receiver: () => 1234,
    mainJS: () => "glue.js",
    build() {
      this.built++;
    },
  };
}

type StartWorkers = (module: unknown, memory: unknown, builder: FakeBuilder) => Promise<void>;

const saved: Record<string, unknown> = {};
let startWorkers: StartWorkers;

beforeAll(async () => {
  const g = globalThis as Record<string, unknown>;
  for (const key of ["self", "Worker", "fetch"]) saved[key] = g[key];
  // The script also runs as a worker's, waiting on `self` for its init message.
  g.self = new EventTarget();
  g.Worker = FakeWorker;
  g.fetch = async () => new Response("// the script");
  // @ts-expect-error: a plain script of the wasm crate's, without types.
  ({ startWorkers } = (await import("../../../crates/up-wasm/src/pool_workers.js")) as { startWorkers: StartWorkers });
});

afterAll(() => {
  Object.assign(globalThis, saved);
});

describe("pool_workers.js", () => {
  it("starts the builder's workers, then lets them go when a fresh instance starts its own", async () => {
    const first = builder(4);
    await startWorkers("module", "memory", first);
    expect(FakeWorker.made).toHaveLength(3);
    expect(first.built).toBe(1);
    expect(FakeWorker.made[0].init).toMatchObject({ type: "up_pool_worker_init", receiver: 1234, mainJS: "glue.js" });
    expect(FakeWorker.made.some((w) => w.terminated)).toBe(false);

    const second = builder(2);
    await startWorkers("module 2", "memory 2", second);
    expect(FakeWorker.made).toHaveLength(4);
    expect(FakeWorker.made.slice(0, 3).every((w) => w.terminated), "the dead instance's workers").toBe(true);
    expect(FakeWorker.made[3].terminated, "the fresh pool's worker").toBe(false);
    expect(second.built).toBe(1);
  });
});
