/*
 * Copyright 2022 Google Inc. All Rights Reserved.
 * Licensed under the Apache License, Version 2.0 (the "License");
 * you may not use this file except in compliance with the License.
 * You may obtain a copy of the License at
 *     http://www.apache.org/licenses/LICENSE-2.0
 * Unless required by applicable law or agreed to in writing, software
 * distributed under the License is distributed on an "AS IS" BASIS,
 * WITHOUT WARRANTIES OR CONDITIONS OF ANY KIND, either express or implied.
 * See the License for the specific language governing permissions and
 * limitations under the License.
 */

// Modified from wasm-bindgen-rayon 1.3.0's src/workerHelpers.no-bundler.js:
// the workers of `initThreadPoolHere` (threads.rs), the pool's threads but
// the one that starts it. It shares that helper's builder protocol
// (numThreads, receiver, mainJS, build); its workers run rayon's loop
// through `up_pool_start_worker`, and the builder is kept for the pool's life.
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
// Kept: the workers read their threads from its channel, by address, after
// `build` has queued them (freeing it under them would be a use after free).
let builderKept;

export async function startWorkers(module, memory, builder) {
  // A second pool comes only from a fresh instance of the module after a
  // trap (every instance's glue imports this one script): the last pool's
  // workers, asleep in the dead instance, are let go with its memory.
  for (const worker of workers ?? []) worker.terminate();
  workers = undefined;
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
  builderKept = builder;
  builder.build();
}
