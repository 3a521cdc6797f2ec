//! The microcontroller builds: the crates that claim `no_std` built for the paper's MCU class
//! (Cortex-M3 without an FPU), with and without their async drivers; the firmware
//! ([`crate::firmware`]) links them for both [`TARGETS`]. rustup adds a missing target and says
//! so.

use crate::run::{cargo, rustup_lines, step};
use anyhow::Result;
use std::path::Path;
use std::process::Command;

/// Cortex-M3 (seed 000's fingertip MCUs), and Cortex-M4F.
pub const TARGETS: [&str; 2] = ["thumbv7m-none-eabi", "thumbv7em-none-eabihf"];

/// The builds' directory, from the workspace root.
const TARGET_DIR: &str = "target/embedded";

/// The crates that say `#![no_std]`, and the features a firmware may turn on.
pub const NO_STD: [(&str, &[&str]); 6] = [
    ("hand-traits", &[]),
    ("baro-drivers", &["async"]),
    ("imu-icm20789", &["async"]),
    ("aot-locate", &[]),
    ("fuzzy-mamdani", &[]),
    ("tactile-nets", &[]),
];

/// Adds the rustup targets in [`TARGETS`] that are missing.
pub fn ensure_targets() -> Result<()> {
    let installed = rustup_lines(
        &["target", "list", "--installed"],
        "the thumb targets of the no_std builds",
    )?;
    for t in TARGETS {
        if !installed.iter().any(|l| l == t) {
            println!("xtask: installing the rustup target {t} (no_std builds)");
            step(
                &format!("rustup target add {t}"),
                Command::new("rustup").args(["target", "add", t]),
            )?;
        }
    }
    Ok(())
}

/// Builds every [`NO_STD`] crate for the first of [`TARGETS`] (Cortex-M3): without default
/// features, then with its firmware features. One target is enough: none of these crates tells
/// the thumb targets apart with a `cfg` (its only target `cfg`s are for x86-64), so the
/// Cortex-M4F's build would compile the same code; the firmware links for both.
pub fn build(root: &Path) -> Result<()> {
    ensure_targets()?;
    let t = TARGETS[0];
    // A build directory of its own: these builds run beside the workspace's (a lane of
    // `cargo xtask test`), which would otherwise wait for each other's lock.
    let mut bare = cargo(root);
    bare.args(["build", "--target", t, "--no-default-features"])
        .env("CARGO_TARGET_DIR", root.join(TARGET_DIR));
    let mut featured = cargo(root);
    featured
        .args(["build", "--target", t, "--no-default-features"])
        .env("CARGO_TARGET_DIR", root.join(TARGET_DIR));
    let mut features = Vec::new();
    for (name, extra) in NO_STD {
        bare.args(["-p", name]);
        featured.args(["-p", name]);
        features.extend(extra.iter().map(|f| format!("{name}/{f}")));
    }
    featured.args(["--features", &features.join(",")]);
    step(&format!("no_std build, {t}"), &mut bare)?;
    step(&format!("no_std build with async, {t}"), &mut featured)
}
