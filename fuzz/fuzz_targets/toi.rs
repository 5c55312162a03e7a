//! libFuzzer's inputs through `up_fuzz::toi::check` (what it checks: src/toi.rs).
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| up_fuzz::toi::check(data));
