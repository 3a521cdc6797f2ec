//! The handstack composition root.
//!
//! A scene file (TOML, `fixtures/scenes/`) names the parts of a tactile hand stack — sensors,
//! estimators, controller, hand, arm — and whether each is simulated or real hardware;
//! `handstack run SCENE` builds exactly those parts and runs the scene's experiment. Every run
//! ends in an [`Outcome`]: the figures the scene measured (beside the paper's, where the paper
//! publishes one) and the data its report draws.

pub mod outcome;
pub mod report;

pub use outcome::{Figure, Line, Outcome, Plot};
