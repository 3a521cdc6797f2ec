//! `cargo xtask trade`: runs `papers trade` under the optimised `test` profile, which
//! measures every speed / accuracy knob in one run and writes `docs/trade.md`, one SVG per
//! task under `docs/trade/` and `docs/trade/points.csv`.

use crate::run::PAPERS;
use anyhow::Result;
use std::path::Path;

/// Runs `cargo xtask trade`.
pub fn run(root: &Path) -> Result<()> {
    PAPERS.run(root, "trade", &["trade"])?;
    println!(
        "trade: report written to {}",
        root.join("docs/trade.md").display()
    );
    Ok(())
}
