#![no_main]
//! `handstack_fuzz::files::fll` under libFuzzer (`cargo xtask fuzz fll`).

libfuzzer_sys::fuzz_target!(|data: &[u8]| handstack_fuzz::files::fll(data));
