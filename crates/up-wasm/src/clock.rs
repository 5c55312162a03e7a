//! The stage clock up-physics reads in the module (`counters::now_ms`
//! declares `up_now_ms`): defined here on the host's `performance.now`, so
//! the module imports nothing but what the wasm-bindgen glue provides.

use wasm_bindgen::prelude::*;

#[wasm_bindgen]
extern "C" {
    #[wasm_bindgen(js_namespace = performance, js_name = now)]
    fn performance_now() -> f64;
}

/// Milliseconds, monotonic (`performance.now()` in the page, its workers and Node).
#[no_mangle]
pub extern "C" fn up_now_ms() -> f64 {
    performance_now()
}
