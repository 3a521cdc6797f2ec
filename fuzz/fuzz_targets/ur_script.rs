#![no_main]
//! `ur_script` under libFuzzer (`cargo xtask fuzz ur_script`): the UR simulator's script intake (ur-sim, port 30003).
//! Written from `handstack_fuzz::TARGETS` by `cargo xtask fuzz --seed`.

libfuzzer_sys::fuzz_target!(|data: &[u8]| handstack_fuzz::run("ur_script", data));
