//! The threaded module's pool: rayon's global pool, whose threads are Web
//! Workers sharing this module's memory (wasm-bindgen-rayon). The glue
//! exports `initThreadPool(n)`, a promise to await once after instantiating
//! the module and before the first step; the pool cannot be resized after
//! (rayon's global pool is built once), so another count needs a fresh
//! instance of the module.

use wasm_bindgen::prelude::*;

pub use wasm_bindgen_rayon::init_thread_pool;

/// Threads in rayon's pool, which step the world. Call it only once
/// `initThreadPool` has resolved: before, it would build rayon's default
/// pool, which cannot start threads in a Web Worker (as a step would).
#[wasm_bindgen]
pub fn thread_count() -> u32 {
    rayon::current_num_threads() as u32
}
