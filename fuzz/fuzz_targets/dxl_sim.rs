#![no_main]
//! `dxl_sim` under libFuzzer (`cargo xtask fuzz dxl_sim`): the simulated servo bus's request handling (dxl-sim).
//! Written from `handstack_fuzz::TARGETS` by `cargo xtask fuzz --seed`.

libfuzzer_sys::fuzz_target!(|data: &[u8]| handstack_fuzz::run("dxl_sim", data));
