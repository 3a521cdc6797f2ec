//! Developer workflows for the handstack workspace, run as `cargo xtask <command>`.
//!
//! - `test`: sets up `.venv`, then fmt check, clippy `-D warnings`, every test, docs, and
//!   `fixtures --check`: the one command CI runs.
//! - `fixtures [--check]`: regenerates every generated fixture, or checks the committed ones.
//! - `bench [FILTER] [-- CRITERION ARGS]`: runs the criterion benches and prints a summary table.
//! - `train contact-mlp`: trains the contact-area MLP, writes its weights, metrics and plot.
//! - `train contact-cnn`: runs the contact CNN's Table I protocol, writes weights, metrics,
//!   plots and its section of `docs/learning.md`.
//! - `demo tap-to-move`: seed 002 §IV-B on the simulated UR3, into `docs/arm-tap-to-move.md`.

pub mod bench;
pub mod demo;
pub mod fixtures;
pub mod fuzzy_peers;
pub mod run;
pub mod test;
pub mod train;
pub mod train_cnn;
pub mod venv;

use std::path::{Path, PathBuf};

/// The workspace root (the parent of `xtask/`).
pub fn workspace_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("xtask lives one level below the workspace root")
        .to_path_buf()
}
