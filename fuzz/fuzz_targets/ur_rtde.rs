#![no_main]
//! `handstack_fuzz::ur::rtde` under libFuzzer (`cargo xtask fuzz ur_rtde`).

libfuzzer_sys::fuzz_target!(|data: &[u8]| handstack_fuzz::ur::rtde(data));
