//! The papers' scenes: seed 000's weight, contact and Table 5 grasp, seed 001's softness and
//! seed 002's tap-to-move, and the full hand as one loop, each a scene file under
//! `fixtures/scenes/` run on the handstack stack with simulated devices behind the real
//! interfaces (or real ones, where a scene names its hardware), plus their HTML report.
//!
//! `paper-scenes run fixtures/scenes/*.toml --report target/demo/report.html` is what
//! `cargo xtask demo` runs. Reproduction only (`publish = false`): it reads the committed
//! models, datasets and paper tables of this workspace.
//!
//! - [`scene`]: paper scene files (handstack's parts, the papers' experiments, hand-sim's
//!   physics);
//! - [`devices`]: each device real or simulated at its real interface;
//! - [`runs`]: one runner per experiment, joined into the scene's `handstack::Outcome`;
//! - [`report`]: the HTML report of a set of outcomes.

#[cfg(feature = "cell")]
pub mod cell;
pub mod devices;
pub mod error;
pub mod report;
pub mod runs;
pub mod scene;

pub use error::Error;

/// Loads the paper scene file at `path` and runs it.
pub fn run_file(
    path: &std::path::Path,
    cx: &runs::RunContext<'_>,
) -> Result<handstack::Outcome, Error> {
    runs::run(&scene::PaperScene::load(path)?, cx)
}
