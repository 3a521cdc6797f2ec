#![no_main]
//! `model` under libFuzzer (`cargo xtask fuzz model`): safetensors model loading and one forward pass (tactile-nets).
//! Written from `handstack_fuzz::TARGETS` by `cargo xtask fuzz --seed`.

libfuzzer_sys::fuzz_target!(|data: &[u8]| handstack_fuzz::run("model", data));
