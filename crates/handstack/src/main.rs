//! `handstack`: run a tactile hand stack from a scene file on its real devices
//! (`handstack run SCENE... [--json]`), or only check scene files (`handstack check SCENE...`).
//! With feature `cell`: a scene's stack as ROS 2 nodes on Zenoh (`handstack node SCENE`, or one
//! part: `--part P [--namespace NS]`), and a cell of such nodes with a coordinator (`handstack
//! cell CELL.toml`).

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
    /// Run a scene's stack (or one part: pad, arm, fingertip or hand) on its real devices as
    /// ROS 2 nodes on Zenoh (rmw_zenoh's conventions), until stdin closes.
    #[cfg(feature = "cell")]
    Node(handstack::cell::cli::NodeCommand),
    /// Start a Zenoh router, the nodes a cell file names (each its own process) and the
    /// coordinator of seed 002's tap-to-move across them.
    #[cfg(feature = "cell")]
    Cell(handstack::cell::cli::CellCommand),
}

fn main() -> ExitCode {
    match Cli::parse().command {
        Command::Run { scenes, json } => run(&scenes, json),
        Command::Check { scenes } => check(&scenes),
        #[cfg(feature = "cell")]
        Command::Node(cmd) => cmd.main(
            || Ok(handstack::cell::scene_parts(&Scene::load(&cmd.scene)?)),
            |args, stop| {
                let scene = Scene::load(&cmd.scene)?;
                handstack::cell::real::run_node(&scene, args, stop)
            },
        ),
        #[cfg(feature = "cell")]
        Command::Cell(cmd) => cmd.main(|path, run| {
            let name = path.file_stem().unwrap_or_default().to_string_lossy();
            handstack::cell::outcome::outcome(&name, run)
        }),
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
