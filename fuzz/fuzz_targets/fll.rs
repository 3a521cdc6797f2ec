#![no_main]
//! `fll` under libFuzzer (`cargo xtask fuzz fll`): fuzzylite .fll import, evaluation and re-export (fuzzy-mamdani).
//! Written from `handstack_fuzz::TARGETS` by `cargo xtask fuzz --seed`.

libfuzzer_sys::fuzz_target!(|data: &[u8]| handstack_fuzz::run("fll", data));
