//! The minimum supported Rust versions: every published crate ([`published_crates`]) checked on
//! the toolchain of the `rust-version` its manifest declares, with every feature, its library
//! and its binaries, against the workspace's `Cargo.lock` (`--locked`: a locked dependency that
//! needs a newer Rust fails the check, as it would for a user on that toolchain). Crates that
//! declare the same version are checked in one `cargo check`; rustup installs a missing
//! toolchain (minimal profile) and says so. The builds go to `target/msrv`, apart from the
//! stable toolchain's.

use crate::architecture::workspace_packages;
use crate::package::published_crates;
use crate::run::{rustup_lines, step};
use anyhow::{Context, Result, bail};
use std::collections::BTreeMap;
use std::path::Path;
use std::process::Command;

/// Each published crate's declared `rust-version` (`cargo metadata --no-deps`), by crate name;
/// fails if a published crate declares none.
pub fn declared(root: &Path) -> Result<BTreeMap<String, String>> {
    let packages = workspace_packages(root)?;
    published_crates(root)?
        .into_iter()
        .map(|name| {
            let package = packages
                .iter()
                .find(|p| p.name == name)
                .with_context(|| format!("published crate {name} is not a workspace member"))?;
            let version = package
                .rust_version
                .clone()
                .with_context(|| format!("published crate {name} declares no rust-version"))?;
            Ok((name, version))
        })
        .collect()
}

/// The rustup toolchain of a `rust-version`: its first release (`1.85` is `1.85.0`, as cargo
/// reads it, not rustup's latest `1.85.x`).
pub fn toolchain(rust_version: &str) -> Result<String> {
    let parts: Vec<&str> = rust_version.split('.').collect();
    if parts.len() > 3
        || parts
            .iter()
            .any(|p| p.is_empty() || !p.bytes().all(|b| b.is_ascii_digit()))
    {
        bail!("rust-version {rust_version:?} is not MAJOR.MINOR[.PATCH]");
    }
    let mut numbers = parts;
    numbers.resize(3, "0");
    Ok(numbers.join("."))
}

/// Installs the rustup toolchain `name` (minimal profile) if it is missing.
pub fn ensure_toolchain(name: &str) -> Result<()> {
    let installed = rustup_lines(
        &["toolchain", "list", "--quiet"],
        "the MSRV check's toolchains",
    )?;
    let prefix = format!("{name}-");
    if !installed
        .iter()
        .any(|l| l == name || l.starts_with(&prefix))
    {
        println!("xtask: installing the Rust {name} toolchain (MSRV check)");
        step(
            &format!("rustup toolchain install {name}"),
            Command::new("rustup").args(["toolchain", "install", name, "--profile", "minimal"]),
        )?;
    }
    Ok(())
}

/// Checks every published crate on the toolchain of its declared `rust-version`, one
/// `rustup run TOOLCHAIN cargo check --locked --all-features --lib --bins -p …` per version.
pub fn check(root: &Path) -> Result<()> {
    let mut groups: BTreeMap<String, Vec<String>> = BTreeMap::new();
    for (name, version) in declared(root)? {
        groups.entry(toolchain(&version)?).or_default().push(name);
    }
    for (toolchain, crates) in &groups {
        ensure_toolchain(toolchain)?;
        let mut cmd = Command::new("rustup");
        cmd.current_dir(root)
            .args([
                "run",
                toolchain,
                "cargo",
                "check",
                "--locked",
                "--all-features",
            ])
            .args(["--lib", "--bins"])
            .env("CARGO_TARGET_DIR", root.join("target/msrv"))
            // `cargo xtask` runs under the stable toolchain: nothing of it may leak in.
            .env_remove("RUSTC")
            .env_remove("RUSTUP_TOOLCHAIN");
        for name in crates {
            cmd.args(["-p", name]);
        }
        step(
            &format!("MSRV check, Rust {toolchain}: {}", crates.join(", ")),
            &mut cmd,
        )?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::toolchain;

    #[test]
    fn a_rust_version_names_its_first_release() {
        assert_eq!(toolchain("1.85").unwrap(), "1.85.0");
        assert_eq!(toolchain("1.87.0").unwrap(), "1.87.0");
        assert_eq!(toolchain("1.85.1").unwrap(), "1.85.1");
        assert!(toolchain("1.85-nightly").is_err());
        assert!(toolchain("").is_err());
    }
}
