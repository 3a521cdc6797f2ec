#![no_main]
//! `handstack_fuzz::dxl::status` under libFuzzer (`cargo xtask fuzz dxl_status`).

libfuzzer_sys::fuzz_target!(|data: &[u8]| handstack_fuzz::dxl::status(data));
