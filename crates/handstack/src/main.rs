//! `handstack`: run a tactile hand stack from a scene file on its real devices
//! (`handstack run SCENE... [--json]`), or only check scene files (`handstack check SCENE...`).

use clap::{Parser, Subcommand};
use handstack::progress::Bars;
use handstack::runs::RunContext;
use handstack::scene::{ExperimentTable as _, Scene};
use std::path::PathBuf;
use std::process::ExitCode;

/// Tactile hand stacks from scene files.
#[derive(Parser)]
#[command(name = "handstack", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Open the devices each scene file names and run its experiments.
    Run {
        /// Scene files.
        #[arg(required = true)]
        scenes: Vec<PathBuf>,
        /// Print the outcomes as JSON on stdout (no progress, no table).
        #[arg(long)]
        json: bool,
    },
    /// Parse and validate scene files without opening anything.
    Check {
        /// Scene files.
        #[arg(required = true)]
        scenes: Vec<PathBuf>,
    },
}

fn main() -> ExitCode {
    match Cli::parse().command {
        Command::Run { scenes, json } => run(&scenes, json),
        Command::Check { scenes } => check(&scenes),
    }
}

fn check(scenes: &[PathBuf]) -> ExitCode {
    let mut failed = false;
    for path in scenes {
        match Scene::load(path) {
            Ok(s) => println!(
                "{}: ok ({})",
                path.display(),
                s.file.experiment.get_ref().names().join(", ")
            ),
            Err(e) => {
                eprintln!("error: {e}");
                failed = true;
            }
        }
    }
    exit(failed)
}

fn run(scenes: &[PathBuf], json: bool) -> ExitCode {
    let bars = Bars::new(!json);
    let cx = RunContext::new(&bars);
    let runs =
        handstack::summary::run_each(scenes, json, &bars, |path| handstack::run_file(path, &cx));
    exit(!runs.failures.is_empty())
}

fn exit(failed: bool) -> ExitCode {
    if failed {
        ExitCode::FAILURE
    } else {
        ExitCode::SUCCESS
    }
}
