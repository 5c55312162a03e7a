//! libFuzzer's inputs through `up_fuzz::contacts::check` (what it checks: src/contacts.rs).
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| up_fuzz::contacts::check(data));
