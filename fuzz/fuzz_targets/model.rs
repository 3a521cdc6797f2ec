#![no_main]
//! `handstack_fuzz::files::model` under libFuzzer (`cargo xtask fuzz model`).

libfuzzer_sys::fuzz_target!(|data: &[u8]| handstack_fuzz::files::model(data));
