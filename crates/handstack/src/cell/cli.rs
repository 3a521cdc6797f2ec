//! The `node` and `cell` commands' arguments and their shared running, for every program that
//! has them (the `handstack` binary on real devices, a reproduction on simulated ones).

use super::NodeArgs;
use super::error::CellError;
use super::file::Part;
use super::launch::{self, CellRun};
use super::pace::Stop;
use crate::Outcome;
use crate::progress::{Bars, Progress as _};
use std::path::{Path, PathBuf};

/// `node SCENE --part P --namespace NS [--connect E] [--domain N] [--humble]`.
#[derive(Debug, Clone, clap::Args)]
pub struct NodeCommand {
    /// The scene file whose part the node runs.
    pub scene: PathBuf,
    /// The part: pad, arm, fingertip or hand.
    #[arg(long)]
    pub part: Part,
    /// The node's namespace (`/arm0`).
    #[arg(long)]
    pub namespace: String,
    /// The Zenoh router to connect to.
    #[arg(long, default_value = "tcp/127.0.0.1:7447")]
    pub connect: String,
    /// ROS domain id.
    #[arg(long, default_value_t = 0)]
    pub domain: u32,
    /// Humble's keys (`TypeHashNotSupported` in place of the type hash).
    #[arg(long)]
    pub humble: bool,
}

impl NodeCommand {
    /// The node's joining options.
    pub fn args(&self) -> NodeArgs {
        NodeArgs {
            part: self.part,
            namespace: self.namespace.clone(),
            connect: self.connect.clone(),
            domain_id: self.domain,
            humble: self.humble,
        }
    }

    /// Runs the node with `run` until stdin closes; prints what it did on stderr.
    pub fn main(
        &self,
        run: impl FnOnce(&NodeArgs, &Stop) -> Result<String, CellError>,
    ) -> std::process::ExitCode {
        let stop = Stop::new();
        stop.on_stdin_eof();
        let args = self.args();
        match run(&args, &stop) {
            Ok(done) => {
                eprintln!("{} {}: {done}", args.namespace, args.part.as_str());
                std::process::ExitCode::SUCCESS
            }
            Err(e) => {
                eprintln!("error: {} {}: {e}", args.namespace, args.part.as_str());
                std::process::ExitCode::FAILURE
            }
        }
    }
}

/// `cell CELL.toml... [--json]`.
#[derive(Debug, Clone, clap::Args)]
pub struct CellCommand {
    /// Cell files.
    #[arg(required = true)]
    pub cells: Vec<PathBuf>,
    /// Print the outcomes as JSON on stdout (no progress, no table).
    #[arg(long)]
    pub json: bool,
}

impl CellCommand {
    /// Runs each cell with this program's `node` command, progress on stderr, a summary table
    /// per cell (or JSON); `outcome` turns a run into its outcome.
    pub fn main(&self, outcome: impl Fn(&Path, &CellRun) -> Outcome) -> std::process::ExitCode {
        let program = match std::env::current_exe() {
            Ok(p) => p,
            Err(e) => {
                eprintln!("error: cannot find this program to start its nodes: {e}");
                return std::process::ExitCode::FAILURE;
            }
        };
        let bars = Bars::new(!self.json);
        let stop = Stop::new();
        let runs = crate::summary::run_each(&self.cells, self.json, &bars, |path| {
            let taps = super::file::CellFile::load(path)?
                .coordinator
                .tap_to_move
                .taps;
            bars.stage("cell: pad node → coordinator → arm node", taps as u64);
            let run = launch::run(path, &program, &stop, |_| bars.advance(1))?;
            Ok::<_, CellError>(outcome(path, &run))
        });
        if runs.failures.is_empty() {
            std::process::ExitCode::SUCCESS
        } else {
            std::process::ExitCode::FAILURE
        }
    }
}
