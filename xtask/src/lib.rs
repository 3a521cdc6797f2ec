//! Developer workflows for the handstack workspace, run as `cargo xtask <command>`.
//!
//! xtask stays thin (rust-analyzer's rule): it parses arguments, sets up `.venv` and Chromium,
//! runs `cargo` and the workspace's binaries — the reproduction's `paper-scenes` (the papers'
//! scenes and report) and `papers` (training, plots, docs sections, simulated datasets, the
//! trade) — and compares the
//! generated fixtures. It links neither the simulator nor the learned models nor plotters, so
//! a first `cargo xtask` compiles in seconds.
//!
//! - `test`: sets up `.venv` and Chromium, then fmt check, clippy `-D warnings`, the `no_std`
//!   crates built for two thumb targets (rustup adds them), the fingertip firmware linked for
//!   both and its pipeline run on the host, the MSRV check of every published crate on its
//!   declared toolchain, `cargo package` of every published crate (product crates and
//!   simulators) with verification and the
//!   consumer test of every README against the packages, every test, docs, and
//!   `fixtures --check` (once more with numpy's widest SIMD kernels off): the one command CI runs.
//! - `fixtures [--check]`: regenerates every generated fixture, or checks the committed ones
//!   (byte for byte, or by value where a third-party library's float code wrote the numbers).
//! - `bench [FILTER] [--write] [-- CRITERION ARGS]`: runs the criterion benches and prints a
//!   summary table; `--write` also writes `docs/benchmarks.md` (machine, date, commit, every
//!   bench, and each scene's control cycle against the 10 ms loop budget).
//! - `train contact-mlp`: trains the contact-area MLP, writes its weights, metrics and plot.
//! - `train contact-cnn`: runs the contact CNN's Table I protocol, writes weights, metrics,
//!   plots and its section of `docs/learning.md`.
//! - `train force-dnn`: trains the force / weight DNN, writes its weights, metrics, training
//!   curve and its section of `docs/learning.md`.
//! - `train softness`: trains the softness classifier (LM and Adam), writes its weights,
//!   metrics, figures and section 2 of `docs/learning.md`.
//!
//!   Each trains with `papers train MODEL`, then draws with `papers docs MODEL` ([`train`]).
//! - `firmware [--write]`: the fingertip firmware (`firmware/fingertip`) linked for both thumb
//!   targets and run on the host; `--write` regenerates `docs/embedded.md`'s figures.
//! - `package`: `cargo package` of every published crate, then the consumer test.
//! - `trade`: the speed / accuracy trade report (`papers trade`) into `docs/trade.md`.
//! - `demo [--screenshot]`: runs every scene in `fixtures/scenes/` on the simulated default
//!   and writes `target/demo/report.html` (`--screenshot`: also `docs/demo-report.png`).
//! - `demo tap-to-move`: seed 002 §IV-B on the simulated UR3, into `docs/arm-tap-to-move.md`.
//! - `cell-doc [--seconds S] [--rounds R]`: the Zenoh cell measured on loopback, into
//!   `docs/cell.md` ([`cell_doc`]).
//! - `soak [--seeds N] [--seconds S]`: the grasp loop under random faults (`papers soak`),
//!   into `docs/reliability.md`.
//! - `fuzz --seed | TARGET… | --all [--seconds N]`: coverage-guided fuzzing with cargo-fuzz
//!   ([`fuzz`]); `test` replays the committed corpora, it does not fuzz.

pub mod architecture;
pub mod bench;
pub mod bench_doc;
pub mod cell_doc;
pub mod chromium;
pub mod consumer;
pub mod demo;
pub mod embedded;
pub mod firmware;
pub mod fixtures;
pub mod fuzz;
pub mod fuzzy_peers;
pub mod lane;
pub mod msrv;
pub mod package;
pub mod run;
pub mod test;
pub mod test_binaries;
pub mod trade;
pub mod train;
pub mod venv;

use std::path::{Path, PathBuf};

/// The workspace root (the parent of `xtask/`).
pub fn workspace_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("xtask lives one level below the workspace root")
        .to_path_buf()
}
