//! handstack: a tactile hand stack from a scene file, on real devices.
//!
//! A scene file (TOML) names the parts of a stack — a barometric fingertip (3 × MS5611 on
//! Linux I2C buses), an ICM-20789 pad, a fuzzy grasp controller, a Dynamixel Protocol 2.0 hand
//! on a serial port, a Universal Robots arm at a host — and what to run on them;
//! `handstack run SCENE` opens exactly those devices (failing, before anything moves, on the
//! first that cannot be opened, naming it and its path) and runs the scene's experiments. Every
//! run ends in an [`Outcome`]: the figures it measured and the data of its plots.
//!
//! ```text
//! cargo install handstack
//! handstack check my-hand.toml
//! handstack run my-hand.toml           # progress on stderr, a summary table on stdout
//! handstack run my-hand.toml --json    # the Outcome, for scripts
//! ```
//!
//! - [`scene`]: the scene schema, parsed with spans and validated (errors name file, line,
//!   column, key and what is allowed); its `[experiment]` table is generic, so a program with
//!   experiments of its own (the papers' reproduction) reads the same parts;
//! - [`stack`]: the real devices a scene names, their buses opened through a
//!   [`Platform`](stack::platform::Platform) (Linux by default, or a substitute);
//! - [`runs`]: the grasp hold, the fingertip readout, weights on the fingertip, the
//!   underactuated hand's softness classification and taps on the pad that move the arm,
//!   joined into the scene's [`Outcome`];
//! - [`pace`]: a loop's period;
//! - [`progress`]: where a run reports its stages;
//! - [`prompt`]: what a run asks its user (place a weight, then press Enter), answered on stdin;
//! - [`record`]: a run recorded as a rosbag2 bag (MCAP) in the nodes' messages and topics, and
//!   read back;
//! - [`collect`]: guided collect sessions, the labelled recordings a user's own models are
//!   trained on; `train` (feature `train`): the user's own force DNN, contact CNN and softness
//!   net from them; [`calibrate`]: the underactuated hand's potentiometers zeroed on the hand;
//! - [`cli`]: the command line, for the `handstack` binary and any program with a platform of its
//!   own;
//! - [`stop`]: what ends a run early (SIGINT, SIGTERM, SIGHUP), through its one shutdown path;
//! - [`tap_to_move`]: a tap on the pad moves the arm to the grid pose of the region it hit
//!   (the loop over `hand-traits` parts, its trigger and its region → grid map), which the
//!   cell runs across processes.
//!
//! Nothing here reads a repository path or holds a simulator: the papers' simulated scenes,
//! their report and the speed / accuracy trade are the reproduction's (`paper-scenes`,
//! `papers`).

pub mod calibrate;
#[cfg(feature = "cell")]
pub mod cell;
pub mod cli;
pub mod collect;
pub mod error;
pub mod outcome;
pub mod pace;
pub mod progress;
pub mod prompt;
pub mod record;
pub mod runs;
pub mod scene;
pub mod stack;
pub mod stop;
pub mod summary;
pub mod tap_to_move;
#[cfg(feature = "train")]
pub mod train;

pub use error::{Ending, RunError};
pub use outcome::{Figure, Line, Outcome, Plot};

/// Loads the scene file at `path` and runs it on its real devices.
pub fn run_file(path: &std::path::Path, cx: &runs::RunContext<'_>) -> Result<Outcome, RunError> {
    runs::run(&scene::Scene::load(path)?, cx)
}

/// The README's examples, compiled with the crate's doctests.
#[doc = include_str!("../README.md")]
#[cfg(doctest)]
pub struct ReadmeDoctests;
