//! The cargo-fuzz project in `fuzz/`, written from [`TARGETS`](crate::TARGETS): each target's
//! `fuzz/fuzz_targets/NAME.rs` and its `[[bin]]` in `fuzz/Cargo.toml`, so the list of targets
//! is stated once. `cargo xtask fuzz --seed` writes them (with the seeds); the corpus test
//! fails when the committed files differ.

use crate::Target;
use std::fmt::Write as _;

/// The line of `fuzz/Cargo.toml` after which everything is [`bins`]: the hand-written part
/// (package, dependencies, profile) stays above it.
pub const BINS_MARKER: &str =
    "# The targets, written from handstack_fuzz::TARGETS by `cargo xtask fuzz --seed`.";

/// `fuzz/fuzz_targets/NAME.rs` of `t`: libFuzzer's entry point around [`crate::run`].
pub fn target_source(t: &Target) -> String {
    format!(
        "#![no_main]\n//! `{name}` under libFuzzer (`cargo xtask fuzz {name}`): {about}.\n//! Written \
         from `handstack_fuzz::TARGETS` by `cargo xtask fuzz --seed`.\n\n\
         libfuzzer_sys::fuzz_target!(|data: &[u8]| handstack_fuzz::run(\"{name}\", data));\n",
        name = t.name,
        about = t.about
    )
}

/// The `[[bin]]` tables of `fuzz/Cargo.toml`, one per target, after [`BINS_MARKER`].
pub fn bins(targets: &[Target]) -> String {
    let mut out = format!("{BINS_MARKER}\n");
    for t in targets {
        // Writing to a `String` cannot fail.
        let _ = write!(
            out,
            "\n[[bin]]\nname = \"{0}\"\npath = \"fuzz_targets/{0}.rs\"\ntest = false\ndoc = false\nbench = false\n",
            t.name
        );
    }
    out
}

/// `manifest` (the committed `fuzz/Cargo.toml`) with everything from [`BINS_MARKER`] on
/// replaced by [`bins`]; `None` if it has no marker line.
pub fn manifest(manifest: &str, targets: &[Target]) -> Option<String> {
    let at = manifest.find(BINS_MARKER)?;
    Some(format!("{}{}", &manifest[..at], bins(targets)))
}
