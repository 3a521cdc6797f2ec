//! After the fuzzy-mamdani bench: times the same reference engine in the Python peers
//! (`python/bench/fuzzy_peers.py`, from the venv) and writes `docs/fuzzy-performance.md`.

use crate::bench::{Measurement, human};
use anyhow::{Context, Result, bail};
use std::path::Path;
use std::process::Command;

/// The criterion id of the reference engine (f64, centroid over 201 samples).
const REFERENCE_ID: &str = "reference_centroid201_f64";

/// Runs the peers and writes the ratio table, if the reference benchmark was measured.
pub fn write_report(root: &Path, measurements: &[Measurement]) -> Result<()> {
    let Some(ours) = measurements.iter().find(|m| m.id == REFERENCE_ID) else {
        return Ok(());
    };
    let python = crate::venv::ensure(root)?;
    let out = Command::new(python)
        .arg(root.join("python/bench/fuzzy_peers.py"))
        .output()?;
    if !out.status.success() {
        bail!(
            "fuzzy_peers.py failed: {}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
    let peers: serde_json::Value =
        serde_json::from_slice(&out.stdout).context("fuzzy_peers.py printed no JSON")?;
    let mut md = String::from(
        "# fuzzy-mamdani performance\n\nWritten by `cargo xtask bench`. The issue-5 reference engine \
         (2 inputs × 9 terms, 81 rules, min / max / min, centroid over 201 samples), one evaluation, \
         on this machine.\n\n| engine | time per evaluation | × fuzzy-mamdani |\n|---|---:|---:|\n",
    );
    md += &format!("| fuzzy-mamdani (f64) | {} | 1 |\n", human(ours.mean_ns));
    for m in measurements.iter().filter(|m| {
        m.id != REFERENCE_ID && (m.id.starts_with("reference_") || m.id.starts_with("grasp_"))
    }) {
        md += &format!(
            "| fuzzy-mamdani `{}` | {} | {:.2} |\n",
            m.id,
            human(m.mean_ns),
            m.mean_ns / ours.mean_ns
        );
    }
    for (name, us) in peers.as_object().into_iter().flatten() {
        let ns = us.as_f64().context("peer time is not a number")? * 1e3;
        md += &format!(
            "| {name} (Python, PyPI) | {} | {:.0} |\n",
            human(ns),
            ns / ours.mean_ns
        );
    }
    let path = root.join("docs/fuzzy-performance.md");
    std::fs::create_dir_all(root.join("docs"))?;
    std::fs::write(&path, md).with_context(|| format!("writing {}", path.display()))?;
    println!("bench: fuzzy peers written to {}", path.display());
    Ok(())
}
