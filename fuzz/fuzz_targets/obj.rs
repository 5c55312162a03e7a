//! libFuzzer's inputs through `up_fuzz::obj::check` (what it checks: src/obj.rs).
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| up_fuzz::obj::check(data));
