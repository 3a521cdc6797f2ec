#![no_main]
//! `ur_dashboard` under libFuzzer (`cargo xtask fuzz ur_dashboard`): the UR simulator's dashboard server (ur-sim, port 29999).
//! Written from `handstack_fuzz::TARGETS` by `cargo xtask fuzz --seed`.

libfuzzer_sys::fuzz_target!(|data: &[u8]| handstack_fuzz::run("ur_dashboard", data));
