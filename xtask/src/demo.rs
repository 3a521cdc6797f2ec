//! `cargo xtask demo [ARGS]`: end-to-end demonstrations.
//!
//! - no argument: every scene in `fixtures/scenes/` on the simulated default, through
//!   `paper-scenes run … --report target/demo/report.html`; prints where the report is.
//! - `--screenshot`: the same, then a full-page screenshot of the report in headless Chromium,
//!   `docs/demo-report.png` (the picture in `docs/demo.md`).
//! - `tap-to-move`: seed 002 §IV-B on the simulated UR3 (ur-sim) through the real ur_rtde
//!   (paper-experiments' `tap_to_move` example), into `docs/arm-tap-to-move.md`.

use crate::run::{cargo, step};
use anyhow::{Context, Result, bail};
use std::path::{Path, PathBuf};

/// The report `cargo xtask demo` writes, relative to the workspace root.
pub const REPORT: &str = "target/demo/report.html";
/// The screenshot `cargo xtask demo --screenshot` writes, relative to the workspace root.
pub const SCREENSHOT: &str = "docs/demo-report.png";

const USAGE: &str = "usage: cargo xtask demo [--screenshot] | demo tap-to-move";

/// Runs the demo `args`.
pub fn run(root: &Path, args: &[String]) -> Result<()> {
    match args {
        [] => scenes(root, false),
        [flag] if flag == "--screenshot" => scenes(root, true),
        [name] if name == "tap-to-move" => tap_to_move(root),
        _ => bail!(USAGE),
    }
}

/// The scene files, sorted by name.
fn scene_files(root: &Path) -> Result<Vec<PathBuf>> {
    let dir = root.join("fixtures/scenes");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .with_context(|| format!("reading {}", dir.display()))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        // Relative to the root (the command's directory): shorter in the run's summary.
        .map(|p| p.strip_prefix(root).map(Path::to_path_buf).unwrap_or(p))
        .collect();
    files.sort();
    if files.is_empty() {
        bail!("no scene files (*.toml) in {}", dir.display());
    }
    Ok(files)
}

fn scenes(root: &Path, screenshot: bool) -> Result<()> {
    // The tap-to-UR3 scene drives the simulated arm through ur_rtde in the venv.
    let python = crate::venv::ensure(root)?;
    let report = root.join(REPORT);
    step(
        "demo: paper-scenes run fixtures/scenes/*.toml",
        cargo(root)
            .args(["run", "--profile", "test", "-p", "paper-scenes", "--"])
            .arg("run")
            .args(scene_files(root)?)
            .arg("--report")
            .arg(&report)
            .env("HANDSTACK_PYTHON", &python),
    )?;
    if screenshot {
        let chromium = crate::chromium::ensure()?;
        step(
            "demo: screenshot",
            cargo(root)
                .args(["run", "--quiet", "--profile", "test", "-p", "paper-scenes"])
                .args(["--example", "report_screenshot", "--"])
                .arg(&report)
                .arg(root.join(SCREENSHOT))
                .env("HANDSTACK_CHROMIUM", chromium),
        )?;
    }
    println!("demo: report written to {}", report.display());
    Ok(())
}

fn tap_to_move(root: &Path) -> Result<()> {
    let python = crate::venv::ensure(root)?;
    let out = root.join("docs/arm-tap-to-move.md");
    step(
        "demo tap-to-move",
        cargo(root)
            .args(["run", "--profile", "test", "-p", "paper-experiments"])
            .args(["--example", "tap_to_move", "--"])
            .arg(&out)
            .env("HANDSTACK_PYTHON", &python),
    )?;
    println!("demo: report written to {}", out.display());
    Ok(())
}
