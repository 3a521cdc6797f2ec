//! `cargo xtask demo NAME`: runs an end-to-end demonstration and writes its report.
//!
//! - `tap-to-move`: seed 002 §IV-B on the simulated UR3 through the real ur_rtde (ur-bridge's
//!   `tap_to_move` example), into `docs/arm-tap-to-move.md`.

use crate::run::{cargo, step};
use anyhow::{Result, bail};
use std::path::Path;

/// Runs the demo `args[0]`.
pub fn run(root: &Path, args: &[String]) -> Result<()> {
    match args {
        [name] if name == "tap-to-move" => {
            let python = crate::venv::ensure(root)?;
            let out = root.join("docs/arm-tap-to-move.md");
            step(
                "demo tap-to-move",
                cargo(root)
                    .args([
                        "run",
                        "--profile",
                        "test",
                        "-p",
                        "ur-bridge",
                        "--features",
                        "sim",
                    ])
                    .args(["--example", "tap_to_move", "--"])
                    .arg(&out)
                    .env("HANDSTACK_PYTHON", &python),
            )?;
            println!("demo: report written to {}", out.display());
            Ok(())
        }
        _ => bail!("usage: cargo xtask demo tap-to-move"),
    }
}
