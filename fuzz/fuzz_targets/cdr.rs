#![no_main]
//! `cdr` under libFuzzer (`cargo xtask fuzz cdr`): CDR message payloads and rmw_zenoh attachments (hand-zenoh).
//! Written from `handstack_fuzz::TARGETS` by `cargo xtask fuzz --seed`.

libfuzzer_sys::fuzz_target!(|data: &[u8]| handstack_fuzz::run("cdr", data));
