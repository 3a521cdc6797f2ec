//! After the fuzzy-mamdani bench: times the same reference engine in the Python peers
//! (`python/bench/fuzzy_peers.py`, from the venv) and writes `docs/fuzzy-performance.md`.

use crate::bench::{Measurement, human};
use anyhow::{Context, Result, bail};
use std::path::Path;
use std::process::Command;

/// Where the crate README's feature table starts and ends.
const FEATURES_BEGIN: &str = "<!-- feature table";
const FEATURES_END: &str = "<!-- /feature table -->";

/// `text` with its one line starting with `prefix` replaced by `line`.
fn replace_line(text: &str, prefix: &str, line: &str) -> Result<String> {
    if !text.lines().any(|l| l.starts_with(prefix)) {
        bail!("no line starting with `{prefix}`");
    }
    let mut out: String = text
        .lines()
        .map(|l| if l.starts_with(prefix) { line } else { l })
        .collect::<Vec<_>>()
        .join("\n");
    out.push('\n');
    Ok(out)
}

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
        "# fuzzy-mamdani performance\n\nWritten by `cargo xtask bench`. The 81-rule reference engine \
         (2 inputs × 9 terms, 81 rules, min / max / min, centroid over 201 points), one evaluation, \
         on this machine, in one run: MATLAB's end-point samples and fuzzylite's midpoints \
         (pyfuzzylite's own rule, so the row to compare with it), and the grasp preset.\n\n\
         | engine | time per evaluation | × fuzzy-mamdani |\n|---|---:|---:|\n",
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
    let mut peer_cells = Vec::new();
    for (name, us) in peers.as_object().into_iter().flatten() {
        let ns = us.as_f64().context("peer time is not a number")? * 1e3;
        md += &format!(
            "| {name} (Python, PyPI) | {} | {:.0} |\n",
            human(ns),
            ns / ours.mean_ns
        );
        peer_cells.push((
            name.clone(),
            format!("{} ({:.0} ×)", human(ns), ns / ours.mean_ns),
        ));
    }
    // The crate README's feature table, copied, and its speed row from this run.
    let readme_path = root.join("crates/fuzzy-mamdani/README.md");
    let readme = std::fs::read_to_string(&readme_path)?;
    let cell = |peer: &str| {
        peer_cells
            .iter()
            .find(|(n, _)| n.contains(peer))
            .map_or_else(|| "—".to_string(), |(_, c)| c.clone())
    };
    let speed = format!(
        "| Speed (81-rule reference engine, one run) | {} | {} | {} |",
        human(ours.mean_ns),
        cell("fuzzylite"),
        cell("scikit"),
    );
    let readme = replace_line(&readme, "| Speed (", &speed)?;
    std::fs::write(&readme_path, &readme)?;
    let (start, end) = (
        readme
            .find(FEATURES_BEGIN)
            .context("README: no feature table")?,
        readme
            .find(FEATURES_END)
            .context("README: no feature table end")?,
    );
    md += "\n## Features against the peers\n\nCopied from the crate README:\n\n";
    md += readme[start..end]
        .lines()
        .filter(|l| !l.starts_with("<!--"))
        .collect::<Vec<_>>()
        .join("\n")
        .trim();
    md += "\n";
    let path = root.join("docs/fuzzy-performance.md");
    std::fs::create_dir_all(root.join("docs"))?;
    std::fs::write(&path, md).with_context(|| format!("writing {}", path.display()))?;
    println!("bench: fuzzy peers written to {}", path.display());
    Ok(())
}
