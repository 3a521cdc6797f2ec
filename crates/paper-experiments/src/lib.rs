//! The three papers' protocols on the simulated datasets: what reproduces a table or a figure
//! and is no part of a crate a user installs. Reproduction only (`publish = false`): it reads
//! the repository's `fixtures/`, trains and evaluates on them, and prints progress.
//!
//! - [`data`]: one reader per committed dataset (fingertip taps and weights, the ICM-20789
//!   pad's windows, the underactuated hand's grasps), each through the file's
//!   `hand_sim::records` schema, into `ndarray` arrays where the data is an array) and the
//!   committed closed-loop grasp results;
//! - [`force_eval`], [`contact_eval`], [`cnn_eval`], [`softness_eval`]: each model's recipes,
//!   held-out protocols and committed models (seed 000 §2.2 and §4, seed 002 §IV-A, seed 001);
//! - [`aot_eval`]: Arrival-of-Time on the fingertip taps (seed 000 §3);
//! - [`contact_location`]: every contact locator on both held-out tap sets against seed 000's
//!   targets, under the border-aware labels (the docs, their drift test and the scene share it);
//! - [`contact_bound`]: the Cramér–Rao bound of the fingertip's forward model, what an
//!   efficient single-cell locator could reach on those sets;
//! - [`jobs`]: the training jobs, and [`train`], the command over them (`papers train MODEL`,
//!   which `cargo xtask train MODEL` runs);
//! - [`trade`]: the speed / accuracy trade (`papers trade`, run by `cargo xtask trade`), with
//!   [`axis`], the chart axes it shares with handstack's report;
//! - [`grasp_rig`]: the Table 5 grasp world (hand-sim's rig and fingertip) behind the grasp
//!   loop's parts (seed 000 §5–7);
//! - `tap_run` (feature `arm`, default): seed 002 §IV-B end to end on hand-sim's pad and the
//!   simulated UR3.
//!
//! The crate's binary, `papers` (`src/bin/papers/`), holds the writers `cargo xtask` runs
//! rather than links, so that xtask stays free of the simulator, the models and plotters:
//! `papers docs MODEL` draws a trained model's plots and rewrites its section of `docs/` from
//! the committed weights and metrics (after `papers train MODEL`), and `papers fixtures NAME
//! --out DIR` writes a simulated dataset (`fixtures/datasets/`) for `cargo xtask fixtures` to
//! compare or commit. xtask builds it without `arm` (no Python):
//! `cargo run --profile test -p paper-experiments --no-default-features --bin papers -- …`.

pub mod aot_eval;
pub mod axis;
pub mod cnn_eval;
pub mod contact_bound;
pub mod contact_eval;
pub mod contact_location;
pub mod force_eval;
pub mod grasp_rig;
pub mod jobs;
pub mod soak;
pub mod softness_eval;
#[cfg(feature = "arm")]
pub mod tap_run;
pub mod trade;
pub mod train;

/// One reader per committed dataset.
pub mod data {
    pub mod fingertip;
    pub mod grasp_results;
    pub mod imu_pad;
    pub mod underactuated;
    pub mod weights;

    pub use hand_sim::records::DatasetError;
}
