// UP's WebAssembly engine in Node, on one thread or on several: the modules
// the page runs (web/public/wasm), for the benchmark and the determinism check.
//
//   import { loadUpWasm } from "../sim-node/loadEngine.mjs";
//   const { glue, memory, threads, close } = await loadUpWasm({ threads: 2 });
//   const engine = new glue.Engine();   // the glue's exports, initialised; memory: the module's
//
// threads = 1: the single-threaded module (up_wasm.wasm) unless `threaded`.
// threads > 1: the threaded one (threads/up_wasm.wasm) with rayon's pool
// started on `threads` workers (wasm-bindgen-rayon's `initThreadPool`); the thread that calls into
// the engine waits while the pool steps. A process holds one pool: its size is
// fixed once started (rayon's global pool), so a second call with another
// count is refused. The pool's workers do not keep the process alive; `close()`
// ends them at once.
//
// Node has no Web Workers: `web-worker` provides them on worker_threads. The
// worker script of wasm-bindgen-rayon (built for pages, no bundler) fetches
// its own file and starts each worker from a blob: URL of it; Node's fetch
// reads no file: URLs and web-worker starts none from blob: URLs, so here
// fetch reads files and such a blob's object URL is a data: URL. These
// shims, `Worker` and an inert `self` (where none is) are set on globalThis
// for the threaded module only.

import { readFile } from "node:fs/promises";
import { existsSync } from "node:fs";
import { fileURLToPath } from "node:url";
import WebWorker from "web-worker";

const wasmDir = new URL("../public/wasm/", import.meta.url);

/** Module and glue of each build: `threaded` picks the threaded one. */
export function modulePaths(threaded) {
  const dir = threaded ? new URL("threads/", wasmDir) : wasmDir;
  return { wasm: new URL("up_wasm.wasm", dir), glue: new URL("up_wasm.js", dir) };
}

/** The pool's workers, to let the process exit or end them. */
const poolWorkers = [];
let started = null;

/** `web-worker`'s Worker, remembered for `close` and to let the process exit. */
class NodeWorker extends WebWorker {
  constructor(url, options) {
    super(url, options);
    poolWorkers.push(this);
  }
}

/** The data: URL standing for each blob read from a file: URL (workers start from data: URLs). */
const dataUrls = new WeakMap();

/** A file's Response whose blob, made into an object URL, is a data: URL. */
class FileResponse extends Response {
  async blob() {
    const blob = await super.blob();
    const bytes = Buffer.from(await blob.arrayBuffer());
    dataUrls.set(blob, `data:text/javascript;base64,${bytes.toString("base64")}`);
    return blob;
  }
}

function installShims() {
  if (globalThis.Worker === NodeWorker) return;
  const nodeFetch = globalThis.fetch;
  globalThis.fetch = async (input, init) => {
    const url = new URL(input instanceof Request ? input.url : String(input));
    if (url.protocol !== "file:") return nodeFetch(input, init);
    return new FileResponse(await readFile(url), { headers: { "content-type": "text/javascript" } });
  };
  // The worker script, imported on this thread too, listens on `self` for a
  // message only its workers get: here a target that none reaches.
  if (globalThis.self === undefined) globalThis.self = new EventTarget();
  const createObjectURL = URL.createObjectURL;
  URL.createObjectURL = (blob) => dataUrls.get(blob) ?? createObjectURL.call(URL, blob);
  globalThis.Worker = NodeWorker;
}

async function start(threads, threaded) {
  const { wasm, glue: gluePath } = modulePaths(threaded);
  for (const file of [wasm, gluePath]) {
    if (!existsSync(file)) {
      const target = threaded ? "web/public/wasm/threads/up_wasm.wasm" : "web/public/wasm/up_wasm.wasm";
      throw new Error(`${fileURLToPath(file)} is missing: build it (make ${target})`);
    }
  }
  if (threaded) installShims();
  const glue = await import(gluePath.href);
  const { memory } = glue.initSync({ module: await readFile(wasm) });
  if (!threaded) return { glue, memory, threads: 1, close: () => {} };
  await glue.initThreadPool(threads);
  // Started: the workers wait in the pool without holding the process open.
  for (const w of poolWorkers) w[Symbol.for("worker")].unref();
  const count = glue.thread_count();
  if (count !== threads) throw new Error(`the thread pool has ${count} threads, ${threads} were asked for`);
  const close = () => {
    for (const w of poolWorkers.splice(0)) w.terminate();
  };
  return { glue, memory, threads: count, close };
}

/**
 * The engine's glue, initialised, on `threads` threads (an integer from 1 to
 * 256): `{ glue, memory, threads, close }` (memory: the module's, for the views of its arrays). `threaded: true` runs the threaded module
 * even on one thread (a pool of one), as the determinism check does.
 */
export async function loadUpWasm({ threads = 1, threaded = threads > 1 } = {}) {
  if (!Number.isInteger(threads) || threads < 1 || threads > 256) {
    throw new Error(`loadUpWasm: threads: expected an integer from 1 to 256, found ${JSON.stringify(threads)}`);
  }
  if (!threaded && threads > 1) throw new Error(`loadUpWasm: ${threads} threads need the threaded module (threaded: true)`);
  if (started) {
    if (started.threads !== threads || started.threaded !== threaded) {
      throw new Error(`loadUpWasm: this process already runs the engine on ${started.threads} thread(s); ${threads} needs another process`);
    }
    return started.loaded;
  }
  const loaded = start(threads, threaded);
  started = { threads, threaded, loaded };
  return loaded;
}
