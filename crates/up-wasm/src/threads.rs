//! The threaded module's pool: rayon's global pool, whose threads are Web
//! Workers sharing this module's memory. Two ways to start it, each once
//! after instantiating the module and before the first step (rayon's global
//! pool is built once; another count needs a fresh instance of the module):
//!
//! - `initThreadPool(n)` (wasm-bindgen-rayon): `n` new workers, beside the
//!   thread that steps the world, which hands each step to them and sleeps
//!   until it is done;
//! - `initThreadPoolHere(n)`: `n − 1` new workers, and the calling thread
//!   (the page's physics worker) the pool's first thread (rayon's
//!   `use_current_thread`): it runs the step and takes its share of every
//!   pass itself, so `n` threads step the world with one worker fewer.
//!
//! `initThreadPoolHere`'s workers are started by `pool_workers.js` (modified
//! from wasm-bindgen-rayon 1.3.0's no-bundler helper, Copyright 2022 Google
//! Inc., Apache License 2.0) and run rayon's loop through
//! `up_pool_start_worker`; `PoolBuilder` and that function follow the same
//! crate's `wbg_rayon_PoolBuilder` and `wbg_rayon_start_worker`.

use std::sync::mpsc::{sync_channel, Receiver, SyncSender};
use std::sync::Mutex;

use js_sys::{JsString, Promise};
use rayon::{ThreadBuilder, ThreadPoolBuilder};
use wasm_bindgen::prelude::*;

pub use wasm_bindgen_rayon::init_thread_pool;

/// Threads in rayon's pool, which step the world. Call it only once
/// `initThreadPool` has resolved: before, it would build rayon's default
/// pool, which cannot start threads in a Web Worker (as a step would).
#[wasm_bindgen]
pub fn thread_count() -> u32 {
    rayon::current_num_threads() as u32
}

/// Whether a step keeps the pool's other threads looking for work through
/// it rather than let them sleep between its passes
/// (`up_physics::set_keep_threads_awake`; on unless turned off).
#[wasm_bindgen]
pub fn set_keep_threads_awake(on: bool) {
    up_physics::set_keep_threads_awake(on);
}

#[wasm_bindgen(module = "/src/pool_workers.js")]
extern "C" {
    #[wasm_bindgen(js_name = startWorkers)]
    fn start_workers(module: JsValue, memory: JsValue, builder: PoolBuilder) -> Promise;
}

#[wasm_bindgen]
extern "C" {
    /// The glue's own URL, which the workers import.
    #[wasm_bindgen(thread_local_v2, js_namespace = ["import", "meta"], js_name = url)]
    static GLUE_URL: JsString;
}

/// The pool being started: the workers to spawn, and the channel on which
/// each receives its rayon thread once all of them run.
#[wasm_bindgen]
pub struct PoolBuilder {
    threads: usize,
    sender: SyncSender<ThreadBuilder>,
    receiver: Mutex<Receiver<ThreadBuilder>>,
}

#[wasm_bindgen]
impl PoolBuilder {
    /// Workers to spawn: the pool's threads but the calling one.
    #[wasm_bindgen(js_name = numThreads)]
    pub fn num_threads(&self) -> usize {
        self.threads - 1
    }

    /// Where the workers find their channel in the shared memory.
    pub fn receiver(&self) -> *const Mutex<Receiver<ThreadBuilder>> {
        &self.receiver
    }

    #[wasm_bindgen(js_name = mainJS)]
    pub fn main_js(&self) -> JsString {
        GLUE_URL.with(Clone::clone)
    }

    /// Builds rayon's global pool with the calling thread as its first
    /// thread; called once every worker waits on the channel. Takes `self`
    /// by reference: the workers hold its receiver's address.
    pub fn build(&mut self) -> Result<(), JsError> {
        ThreadPoolBuilder::new()
            .num_threads(self.threads)
            .use_current_thread()
            .spawn_handler(|thread| {
                self.sender
                    .send(thread)
                    .map_err(|e| std::io::Error::other(e.to_string()))
            })
            .build_global()
            .map_err(|e| JsError::new(&format!("the thread pool: {e}")))
    }
}

/// Starts rayon's global pool on `threads` threads (at least 2), this one the
/// first; resolves once every thread runs.
#[wasm_bindgen(js_name = initThreadPoolHere)]
pub fn init_thread_pool_here(threads: usize) -> Result<Promise, JsError> {
    if threads < 2 {
        return Err(JsError::new(&format!(
            "a pool with the calling thread needs 2 threads or more, {threads} were asked for"
        )));
    }
    let (sender, receiver) = sync_channel(threads);
    let builder = PoolBuilder {
        threads,
        sender,
        receiver: Mutex::new(receiver),
    };
    Ok(start_workers(
        wasm_bindgen::module(),
        wasm_bindgen::memory(),
        builder,
    ))
}

/// A worker of `initThreadPoolHere`'s pool: takes its rayon thread from the
/// builder's channel and runs rayon's loop for good.
#[wasm_bindgen]
#[allow(clippy::not_unsafe_ptr_arg_deref)]
pub fn up_pool_start_worker(
    receiver: *const Mutex<Receiver<ThreadBuilder>>,
) -> Result<(), JsError> {
    // Safe while the builder lives: pool_workers.js keeps it for the pool's
    // life (`build` may return before every worker has taken its thread).
    let receiver = unsafe { &*receiver };
    let thread = receiver
        .lock()
        .map_err(|_| JsError::new("the thread pool's channel was poisoned"))?
        .recv()
        .map_err(|e| JsError::new(&format!("the thread pool's channel: {e}")))?;
    thread.run();
    Ok(())
}
