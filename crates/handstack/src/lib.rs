//! The handstack composition root.
//!
//! A scene file (TOML, `fixtures/scenes/`) names the parts of a tactile hand stack — sensors,
//! estimators, controller, hand, arm — and whether each is simulated or real hardware;
//! `handstack run SCENE` builds exactly those parts and runs the scene's experiment. Every run
//! ends in an [`Outcome`]: the figures the scene measured (beside the paper's, where the paper
//! publishes one) and the data its report draws.
//!
//! - [`scene`]: the scene schema, parsed with spans and validated (errors name file, line,
//!   column, key and what is allowed);
//! - [`runs`]: one runner per experiment, joined into the scene's [`Outcome`];
//! - [`progress`]: where a run reports its stages.
//!
//! The papers' training (`papers train MODEL`) and speed / accuracy trade (`papers trade`) are
//! the reproduction's: `paper_experiments::{train, trade}`.

pub mod error;
pub mod outcome;
pub mod progress;
pub mod report;
pub mod runs;
pub mod scene;
pub mod stack;
pub mod summary;

pub use error::RunError;
pub use outcome::{Figure, Line, Outcome, Plot};

/// Loads the scene file at `path` and runs it.
pub fn run_file(path: &std::path::Path, cx: &runs::RunContext<'_>) -> Result<Outcome, RunError> {
    runs::run(&scene::Scene::load(path)?, cx)
}
