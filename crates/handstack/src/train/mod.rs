//! `handstack train` (feature `train`): a user's own models from their collect sessions,
//! written as weights files a scene names, with their held-out figures and cost.

pub mod force;

use crate::Outcome;
use crate::record::read::ReadError;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use tactile_nets::NetError;

/// Why a model could not be trained or written.
#[derive(Debug, thiserror::Error)]
pub enum TrainError {
    /// A session's bag cannot be read or lacks what training needs.
    #[error(transparent)]
    Read(#[from] ReadError),
    /// Too few distinct steps to hold some out.
    #[error(
        "{found} {what} recorded: training holds every fourth out (never the lightest or the \
         heaviest) to test the model on, so it needs at least {needed}; collect more \
         (`handstack collect SCENE --into DIR`)"
    )]
    TooFew {
        /// What was counted (`weights`).
        what: &'static str,
        /// How many the sessions have.
        found: usize,
        /// How many are needed.
        needed: usize,
    },
    /// Training itself failed (a non-finite sample, a diverging fit).
    #[error("training failed: {0}")]
    Net(#[from] NetError),
    /// The output file exists already.
    #[error("{} exists: name a new file, or remove it first", path.display())]
    Exists {
        /// The file.
        path: PathBuf,
    },
    /// The weights or metrics could not be written.
    #[error("cannot write {}: {reason}", path.display())]
    Write {
        /// The file.
        path: PathBuf,
        /// The system's answer.
        reason: String,
    },
}

/// `handstack train`'s arguments.
#[derive(clap::Args)]
pub struct TrainCommand {
    #[command(subcommand)]
    model: Model,
}

#[derive(clap::Subcommand)]
enum Model {
    /// The force / weight DNN (Kim et al. 2020, §2.2) from `[experiment.weight]` sessions.
    Force(force::ForceArgs),
}

impl TrainCommand {
    /// Trains, prints the figures (a table, or JSON) and writes the files.
    pub fn main(&self) -> ExitCode {
        let ran = match &self.model {
            Model::Force(args) => args.run(),
        };
        match ran {
            Ok((outcome, json)) => {
                if json {
                    match serde_json::to_string_pretty(&outcome) {
                        Ok(s) => println!("{s}"),
                        Err(e) => eprintln!("error: cannot write JSON: {e}"),
                    }
                } else {
                    println!("{}", crate::summary::table(&outcome));
                    for note in &outcome.notes {
                        println!("  {note}");
                    }
                }
                ExitCode::SUCCESS
            }
            Err(e) => {
                eprintln!("error: {e}");
                ExitCode::from(crate::error::EXIT_NOT_STARTED)
            }
        }
    }
}

/// The metrics file written beside weights file `weights`: `my-tip.safetensors` →
/// `my-tip.metrics.json`.
pub fn metrics_path(weights: &Path) -> PathBuf {
    weights.with_extension("metrics.json")
}

/// Fails when `path` exists (training never overwrites a file).
fn refuse_existing(path: &Path) -> Result<(), TrainError> {
    if path.exists() {
        return Err(TrainError::Exists {
            path: path.to_owned(),
        });
    }
    Ok(())
}

/// Writes `outcome` as JSON to `path`.
fn write_metrics(path: &Path, outcome: &Outcome) -> Result<(), TrainError> {
    let write = |reason: String| TrainError::Write {
        path: path.to_owned(),
        reason,
    };
    let text = serde_json::to_string_pretty(outcome).map_err(|e| write(e.to_string()))?;
    std::fs::write(path, text + "\n").map_err(|e| write(e.to_string()))
}

/// The median time of one call of `f`, ns: 15 repeats of 1 000 calls (the trade report's cost
/// measure, on this machine).
pub fn cost_ns(mut f: impl FnMut()) -> f64 {
    let mut per_call: Vec<f64> = (0..15)
        .map(|_| {
            let t = std::time::Instant::now();
            for _ in 0..1000 {
                f();
            }
            t.elapsed().as_secs_f64() * 1e6
        })
        .collect();
    per_call.sort_by(f64::total_cmp);
    per_call[per_call.len() / 2]
}
