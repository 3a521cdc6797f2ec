#![no_main]
//! `fis` under libFuzzer (`cargo xtask fuzz fis`): MATLAB .fis import, evaluation and re-export (fuzzy-mamdani).
//! Written from `handstack_fuzz::TARGETS` by `cargo xtask fuzz --seed`.

libfuzzer_sys::fuzz_target!(|data: &[u8]| handstack_fuzz::run("fis", data));
