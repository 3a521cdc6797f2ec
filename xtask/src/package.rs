//! The published crates as crates.io would get them: `cargo package` of every published crate
//! (kinds `product`, `driver` and `simulator` in `docs/architecture.md`'s rules table), each
//! verified by building it from its packaged files alone, the workspace's own crates among its
//! dependencies taken from the packages just made.

use crate::architecture::parse_rules;
use crate::run::{cargo, step, workspace_test_profile};
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

/// Packages and verifies every published crate (uncommitted edits included).
pub fn run(root: &Path) -> Result<()> {
    let crates = published_crates(root)?;
    forget_unpacked_packages(&crates)?;
    let mut cmd = cargo(root);
    workspace_test_profile(&mut cmd, root)?;
    cmd.args(["package", "--allow-dirty"]);
    for name in &crates {
        cmd.args(["-p", name]);
    }
    step("package the published crates", &mut cmd)
}

/// Removes our crates' copies that an earlier `cargo package` unpacked from its temporary
/// registry (`$CARGO_HOME/registry/src/-HASH/NAME-VERSION`; local registries have no host in
/// the folder name). The version stays 0.1.0 while the code changes, and cargo does not
/// unpack a version it finds unpacked, so a later verify would build a dependent against an
/// earlier commit's code (seen: `handstack` against an `imu-icm20789` without `read_frame`).
fn forget_unpacked_packages(crates: &[String]) -> Result<()> {
    let home = std::env::var_os("CARGO_HOME")
        .map(std::path::PathBuf::from)
        .or_else(|| std::env::var_os("HOME").map(|h| Path::new(&h).join(".cargo")));
    let Some(src) = home.map(|h| h.join("registry/src")) else {
        return Ok(());
    };
    let Ok(registries) = std::fs::read_dir(&src) else {
        return Ok(());
    };
    for registry in registries.flatten() {
        if !registry.file_name().to_string_lossy().starts_with('-') {
            continue;
        }
        for unpacked in std::fs::read_dir(registry.path())?.flatten() {
            let name = unpacked.file_name().to_string_lossy().into_owned();
            let ours = crates.iter().any(|c| {
                name.strip_prefix(c.as_str())
                    .and_then(|rest| rest.strip_prefix('-'))
                    .is_some_and(|v| v.starts_with(|ch: char| ch.is_ascii_digit()))
            });
            if ours {
                std::fs::remove_dir_all(unpacked.path())
                    .with_context(|| format!("removing {}", unpacked.path().display()))?;
            }
        }
    }
    Ok(())
}
