#![no_main]
//! `handstack_fuzz::files::dataset` under libFuzzer (`cargo xtask fuzz dataset`).

libfuzzer_sys::fuzz_target!(|data: &[u8]| handstack_fuzz::files::dataset(data));
