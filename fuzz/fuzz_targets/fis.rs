#![no_main]
//! `handstack_fuzz::files::fis` under libFuzzer (`cargo xtask fuzz fis`).

libfuzzer_sys::fuzz_target!(|data: &[u8]| handstack_fuzz::files::fis(data));
