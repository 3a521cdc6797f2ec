#![no_main]
//! `handstack_fuzz::network::cdr` under libFuzzer (`cargo xtask fuzz cdr`).

libfuzzer_sys::fuzz_target!(|data: &[u8]| handstack_fuzz::network::cdr(data));
