//! libFuzzer's inputs through `up_fuzz::scene::check` (what it checks: src/scene.rs).
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| up_fuzz::scene::check(data));
