#![no_main]
//! `dxl_status` under libFuzzer (`cargo xtask fuzz dxl_status`): Protocol 2.0 framing and the driver's status-packet checks (hand-control).
//! Written from `handstack_fuzz::TARGETS` by `cargo xtask fuzz --seed`.

libfuzzer_sys::fuzz_target!(|data: &[u8]| handstack_fuzz::run("dxl_status", data));
