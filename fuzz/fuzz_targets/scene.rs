#![no_main]
//! `handstack_fuzz::files::scene` under libFuzzer (`cargo xtask fuzz scene`).

libfuzzer_sys::fuzz_target!(|data: &[u8]| handstack_fuzz::files::scene(data));
