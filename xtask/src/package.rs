//! The published crates as crates.io would get them: `cargo package` of every product crate
//! (kinds `product` and `driver` in `docs/architecture.md`'s rules table), each verified by
//! building it from its packaged files alone, the workspace's own crates among its
//! dependencies taken from the packages just made.

use crate::architecture::parse_rules;
use crate::run::{cargo, step};
use anyhow::{Context, Result};
use std::path::Path;

/// The product crates of the rules table, by name.
pub fn product_crates(root: &Path) -> Result<Vec<String>> {
    let doc = std::fs::read_to_string(root.join("docs/architecture.md"))
        .context("docs/architecture.md")?;
    Ok(parse_rules(&doc)?
        .into_iter()
        .filter(|(_, rule)| rule.kind.is_product())
        .map(|(name, _)| name)
        .collect())
}

/// Packages and verifies every product crate (uncommitted edits included).
pub fn run(root: &Path) -> Result<()> {
    let mut cmd = cargo(root);
    cmd.args(["package", "--allow-dirty"]);
    for name in product_crates(root)? {
        cmd.args(["-p", &name]);
    }
    step("package the product crates", &mut cmd)
}
