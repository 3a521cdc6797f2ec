//! Running the steps of a workflow: one announced, timed child process at a time.

use anyhow::{Context, Result, bail};
use std::path::Path;
use std::process::Command;
use std::time::Instant;

/// `cargo` as the running toolchain names it, started in the workspace root.
pub fn cargo(root: &Path) -> Command {
    let mut cmd = Command::new(std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into()));
    cmd.current_dir(root);
    cmd
}

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

/// Runs the `handstack` binary as the step `name` under the optimised `test` profile (the
/// profile the tests build, so nothing is compiled twice): `handstack ARGS --root ROOT`.
pub fn handstack(root: &Path, name: &str, args: &[&str]) -> Result<()> {
    step(
        name,
        cargo(root)
            .args([
                "run",
                "--quiet",
                "--profile",
                "test",
                "-p",
                "handstack",
                "--",
            ])
            .args(args)
            .arg("--root")
            .arg(root),
    )
}
