#![no_main]
//! `fingertip_link` under libFuzzer (`cargo xtask fuzz fingertip_link`): the host's reader of the fingertip microcontroller's UART frames (fingertip-link).
//! Written from `handstack_fuzz::TARGETS` by `cargo xtask fuzz --seed`.

libfuzzer_sys::fuzz_target!(|data: &[u8]| handstack_fuzz::run("fingertip_link", data));
