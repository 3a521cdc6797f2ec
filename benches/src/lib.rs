//! One full control cycle per handstack scene, composed from the crates' real code paths with
//! in-process simulated devices (no pty, no socket, no Python): sensor decode → estimate →
//! policy → command encode. The criterion benches (`benches/cycles.rs`, run by
//! `cargo xtask bench cycles`) and the tests (`tests/`) drive the same structs, so a bench
//! measures exactly what a test checks.
//!
//! | scene | decode | estimate | policy | encode |
//! |---|---|---|---|---|
//! | [`weight`] | 3 × MS5611 (chip models, real driver, scheduler) | rises over the resting tare | force DNN (frozen) | — |
//! | [`contact`] | 3 × MS5611 | arrival detection | AoT eq. 3 and ranging, contact MLP | — |
//! | [`grasp`] | 3 × MS5611 | tared mean + filtered rate (hand-control) | fuzzy preset + Table 5 band | MX-28 Goal PWM / Goal Position sync writes |
//! | [`softness`] | 4 FSR + 4 potentiometer ADC codes → SI (hand-sim's calibration) | 8-variable sample | softness net, running class | — |
//! | [`tap`] | ICM-20789 frame (chip model, real driver) | 4 × 38 window | contact CNN (frozen) → region | UR3 grid pose |
//! | [`full_hand`] | all of the above in one cycle | | | |
//!
//! The full hand is benched as a whole cycle only: its stages are the scenes' stages.
//! [`workloads`] lists every benchmark (the stages, the cycles and the compute kernels) once, for
//! criterion's wall time and callgrind's instruction counts alike.
//!
//! # Allocations
//!
//! `tests/alloc/zero_alloc.rs` counts heap blocks (dhat) over 500 cycles after a 200-cycle warm-up:
//! none in any scene's cycle, the contact MLP's calls counted apart and none there either. It
//! also prints each scene's peak heap (one child process per scene).
//! `tests/alloc/grasp_loop_log.rs` measures `GraspLoop::cycle` itself over the grasp scene's parts:
//! its only allocations are its per-cycle log `Vec` growing (one sample a cycle, a reallocation
//! per doubling), which is why the grasp scene's cycle calls the loop's steps one by one.
//!
//! Every scene exposes its stages as methods, and `cycle` calls them in order:
//!
//! ```
//! use handstack_benches::grasp::GraspCycle;
//! let mut g = GraspCycle::new()?;
//! let out = g.cycle()?;
//! assert!(out.packets.is_empty()); // the first frames tare the estimator
//! for _ in 0..handstack_benches::grasp::TARE_FRAMES {
//!     g.cycle()?;
//! }
//! assert_eq!(g.cycle()?.packets.len(), GraspCycle::WIRE_LEN); // Goal PWM + Goal Position
//! # Ok::<(), handstack_benches::CycleError>(())
//! ```

pub mod contact;
mod error;
pub mod fingertip;
pub mod full_hand;
pub mod grasp;
pub mod replay;
pub mod softness;
pub mod tap;
pub mod weight;
pub mod workloads;

/// The fuzzy benches' reference engine (81 rules), shared with fuzzy-mamdani's tests.
#[path = "../../crates/fuzzy-mamdani/tests/common/mod.rs"]
mod fuzzy_reference;

pub use error::CycleError;

use std::path::PathBuf;

/// The control loop period every cycle is compared with: the grasp loop's default, 10 ms
/// (100 Hz).
pub const LOOP_BUDGET_NS: f64 =
    hand_control::grasp_loop::LoopConfig::DEFAULT_PERIOD_US as f64 * 1e3;

/// The workspace root (committed models are read from it).
pub fn workspace_root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .map(PathBuf::from)
        .unwrap_or_default()
}
