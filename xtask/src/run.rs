//! Running the steps of a workflow: one announced, timed child process at a time.

use anyhow::{Context, Result, bail};
use std::ffi::OsStr;
use std::path::Path;
use std::process::Command;
use std::time::Instant;

/// `cargo` as the running toolchain names it, started in the workspace root.
pub fn cargo(root: &Path) -> Command {
    let mut cmd = Command::new(std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into()));
    cmd.current_dir(root);
    cmd
}

/// Gives `cmd`, a cargo build of a manifest outside the workspace (a packaged crate being
/// verified, the consumer crate), the settings of the workspace's `[profile.test]`
/// (`opt-level`, `debug`, no incremental cache) for its `dev` profile: such a manifest does not
/// read the workspace's profiles. With the same settings its third-party crates hash as the
/// test build's do and land in the same `target/debug`, so `cargo xtask test` compiles each of
/// them once, not once per profile; with cargo's defaults (full debug info, incremental) those
/// builds also wrote 3.8 GB and once filled CI's disk.
pub fn workspace_test_profile(cmd: &mut Command) -> &mut Command {
    cmd.env("CARGO_PROFILE_DEV_OPT_LEVEL", TEST_OPT_LEVEL)
        .env("CARGO_PROFILE_DEV_DEBUG", DEV_DEBUG)
        .env("CARGO_INCREMENTAL", "0")
}

/// The workspace's `[profile.dev] debug`, which `[profile.test]` inherits (root `Cargo.toml`;
/// a test holds the two together).
const DEV_DEBUG: &str = "line-tables-only";

/// The workspace's `[profile.test] opt-level` (root `Cargo.toml`; a test holds the two together).
const TEST_OPT_LEVEL: &str = "2";

/// Runs `cmd` as the step `name`, printing its name and wall time; fails if it fails.
pub fn step(name: &str, cmd: &mut Command) -> Result<()> {
    println!("==> {name}");
    let start = Instant::now();
    let status = cmd
        .status()
        .with_context(|| format!("{name}: could not start {cmd:?}"))?;
    let secs = start.elapsed().as_secs_f64();
    if !status.success() {
        bail!("{name} failed after {secs:.1} s ({status})");
    }
    println!("    {name}: ok in {secs:.1} s");
    Ok(())
}

/// The lines `rustup ARGS` prints (what is installed), trimmed; `why` says what needs rustup.
pub fn rustup_lines(args: &[&str], why: &str) -> Result<Vec<String>> {
    let out = Command::new("rustup")
        .args(args)
        .output()
        .with_context(|| format!("rustup is needed for {why}"))?;
    if !out.status.success() {
        bail!(
            "rustup {} failed: {}",
            args.join(" "),
            String::from_utf8_lossy(&out.stderr)
        );
    }
    Ok(String::from_utf8_lossy(&out.stdout)
        .lines()
        .map(|l| l.trim().to_owned())
        .collect())
}

/// A workspace binary that a workflow runs through `cargo run`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Binary {
    /// The package that holds it.
    pub package: &'static str,
    /// The `[[bin]]` name.
    pub name: &'static str,
    /// Build the package with its default features.
    pub default_features: bool,
}

/// The reproduction's writers: training (`train MODEL`: weights and metrics), a model's plots
/// and docs, the simulated datasets, the speed / accuracy trade. Without the default `arm`
/// feature: they need no Python, so the binary embeds none.
pub const PAPERS: Binary = Binary {
    package: "paper-experiments",
    name: "papers",
    default_features: false,
};

impl Binary {
    /// `cargo run --quiet --profile test -p PACKAGE [--no-default-features] --bin NAME -- ARGS
    /// --root ROOT`, under the optimised `test` profile: the profile the tests build, so nothing
    /// is compiled twice, and numeric code runs several times faster than at `opt-level = 0`.
    pub fn command<S: AsRef<OsStr>>(&self, root: &Path, args: &[S]) -> Command {
        let mut cmd = cargo(root);
        cmd.args(["run", "--quiet", "--profile", "test", "-p", self.package]);
        if !self.default_features {
            cmd.arg("--no-default-features");
        }
        cmd.args(["--bin", self.name, "--"])
            .args(args)
            .arg("--root")
            .arg(root);
        cmd
    }

    /// Runs `self ARGS --root ROOT` ([`Binary::command`]) as the step `name`.
    pub fn run<S: AsRef<OsStr>>(&self, root: &Path, name: &str, args: &[S]) -> Result<()> {
        step(name, &mut self.command(root, args))
    }
}

#[cfg(test)]
mod tests {
    /// The value of `key` in the root `Cargo.toml`'s `[profile.NAME]` section.
    fn profile_setting(name: &str, key: &str) -> String {
        let manifest = std::fs::read_to_string(crate::workspace_root().join("Cargo.toml")).unwrap();
        let section = manifest
            .split(&format!("[profile.{name}]"))
            .nth(1)
            .and_then(|rest| rest.split("\n[").next())
            .unwrap_or_else(|| panic!("a [profile.{name}] section"));
        section
            .lines()
            .find_map(|l| l.trim().strip_prefix(key)?.trim().strip_prefix('='))
            .map(|v| v.trim().trim_matches('"').to_owned())
            .unwrap_or_else(|| panic!("[profile.{name}] sets no {key}"))
    }

    /// [`super::DEV_DEBUG`] and [`super::TEST_OPT_LEVEL`] are what the root `Cargo.toml` sets.
    #[test]
    fn the_outside_builds_use_the_workspaces_test_settings() {
        assert_eq!(profile_setting("dev", "debug"), super::DEV_DEBUG);
        assert_eq!(profile_setting("test", "opt-level"), super::TEST_OPT_LEVEL);
        assert_eq!(profile_setting("test", "incremental"), "false");
    }
}
