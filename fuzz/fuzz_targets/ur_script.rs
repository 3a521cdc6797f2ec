#![no_main]
//! `handstack_fuzz::ur::script` under libFuzzer (`cargo xtask fuzz ur_script`).

libfuzzer_sys::fuzz_target!(|data: &[u8]| handstack_fuzz::ur::script(data));
