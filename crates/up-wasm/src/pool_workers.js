// The workers of `initThreadPoolHere` (threads.rs): the pool's threads but the
// one that starts it. Kept close to wasm-bindgen-rayon's no-bundler helper
// (Copyright 2022 Google Inc., Apache License 2.0), whose builder protocol
// (numThreads, receiver, mainJS, build) it shares; its workers run rayon's
// loop through `up_pool_start_worker`.
//
// This file is both the starter (imported by the glue) and, fetched as a
// blob, each worker's script: a worker waits for its init message.

function waitForMsgType(target, type) {
  return new Promise((resolve) => {
    target.addEventListener("message", function onMsg({ data }) {
      if (data == null || data.type !== type) return;
      target.removeEventListener("message", onMsg);
      resolve(data);
    });
  });
}

waitForMsgType(self, "up_pool_worker_init").then(async (data) => {
  const pkg = await import(data.mainJS);
  await pkg.default({ module_or_path: data.module, memory: data.memory });
  postMessage({ type: "up_pool_worker_ready" });
  pkg.up_pool_start_worker(data.receiver);
});

// Kept, so that no browser collects a worker sharing the module's memory
// while nothing else refers to it (Firefox's bug 1702191).
let workers;

export async function startWorkers(module, memory, builder) {
  const init = {
    type: "up_pool_worker_init",
    module,
    memory,
    receiver: builder.receiver(),
    mainJS: builder.mainJS(),
  };
  workers = await Promise.all(
    Array.from({ length: builder.numThreads() }, async () => {
      // A blob of this very script: a worker from another origin's URL would be refused.
      const script = await fetch(import.meta.url).then((r) => r.blob());
      const url = URL.createObjectURL(script);
      const worker = new Worker(url, { type: "module" });
      worker.postMessage(init);
      await waitForMsgType(worker, "up_pool_worker_ready");
      URL.revokeObjectURL(url);
      return worker;
    }),
  );
  builder.build();
}
