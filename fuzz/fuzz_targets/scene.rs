#![no_main]
//! `scene` under libFuzzer (`cargo xtask fuzz scene`): scene TOML parsing and validation, and the error text (handstack).
//! Written from `handstack_fuzz::TARGETS` by `cargo xtask fuzz --seed`.

libfuzzer_sys::fuzz_target!(|data: &[u8]| handstack_fuzz::run("scene", data));
