//! The published crates as crates.io would get them: `cargo package` of every published crate
//! (kinds `product`, `driver` and `simulator` in `docs/architecture.md`'s rules table). The
//! consumer test ([`crate::consumer`]) then builds every package's library and binaries from its
//! packaged files alone, the workspace's own crates among their dependencies taken from the
//! packages just made: what cargo's own verify builds, once for all of them.

use crate::architecture::parse_rules;
use crate::run::{cargo, step};
use anyhow::{Context, Result};
use std::path::Path;

/// The published crates of the rules table (product crates, drivers and simulators), by name.
pub fn published_crates(root: &Path) -> Result<Vec<String>> {
    let doc = std::fs::read_to_string(root.join("docs/architecture.md"))
        .context("docs/architecture.md")?;
    Ok(parse_rules(&doc)?
        .into_iter()
        .filter(|(_, rule)| rule.kind.is_published())
        .map(|(name, _)| name)
        .collect())
}

/// Packages every published crate (uncommitted edits included), without cargo's verify build:
/// cargo verifies each package in a build of its own, one after the other (13 builds, each
/// ending on one core), where the consumer test builds the same packaged files in one.
pub fn run(root: &Path) -> Result<()> {
    let crates = published_crates(root)?;
    let mut cmd = cargo(root);
    cmd.args(["package", "--allow-dirty", "--no-verify"]);
    for name in &crates {
        cmd.args(["-p", name]);
    }
    step("package the published crates", &mut cmd)
}
