#![no_main]
//! `handstack_fuzz::dxl::sim` under libFuzzer (`cargo xtask fuzz dxl_sim`).

libfuzzer_sys::fuzz_target!(|data: &[u8]| handstack_fuzz::dxl::sim(data));
