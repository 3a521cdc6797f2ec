#![no_main]
//! `dataset` under libFuzzer (`cargo xtask fuzz dataset`): the datasets' CSV readers (paper-experiments).
//! Written from `handstack_fuzz::TARGETS` by `cargo xtask fuzz --seed`.

libfuzzer_sys::fuzz_target!(|data: &[u8]| handstack_fuzz::run("dataset", data));
