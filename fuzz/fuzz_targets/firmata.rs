#![no_main]
//! `firmata` under libFuzzer (`cargo xtask fuzz firmata`): the host's Firmata parser on a board's byte stream (firmata-host).
//! Written from `handstack_fuzz::TARGETS` by `cargo xtask fuzz --seed`.

libfuzzer_sys::fuzz_target!(|data: &[u8]| handstack_fuzz::run("firmata", data));
