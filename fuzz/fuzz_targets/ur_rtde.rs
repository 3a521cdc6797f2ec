#![no_main]
//! `ur_rtde` under libFuzzer (`cargo xtask fuzz ur_rtde`): the UR simulator's RTDE server (ur-sim, port 30004).
//! Written from `handstack_fuzz::TARGETS` by `cargo xtask fuzz --seed`.

libfuzzer_sys::fuzz_target!(|data: &[u8]| handstack_fuzz::run("ur_rtde", data));
