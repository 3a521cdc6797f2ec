#![no_main]
//! `handstack_fuzz::ur::dashboard` under libFuzzer (`cargo xtask fuzz ur_dashboard`).

libfuzzer_sys::fuzz_target!(|data: &[u8]| handstack_fuzz::ur::dashboard(data));
