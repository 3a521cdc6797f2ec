//! The `node` and `cell` commands' arguments and their shared running, for every program that
//! has them (the `handstack` binary on real devices, a reproduction on simulated ones).

use super::NodeArgs;
use super::error::CellError;
use super::file::Part;
use super::launch::{self, CellRun};
use crate::Outcome;
use crate::progress::{Bars, Progress as _};
use crate::stop::{Stop, StopReason};
use std::path::{Path, PathBuf};

/// `node SCENE [--part P [--namespace NS]] [--connect E] [--domain N] [--humble]`.
#[derive(Debug, Clone, clap::Args)]
pub struct NodeCommand {
    /// The scene file whose stack (or part) the node runs.
    pub scene: PathBuf,
    /// One part: pad, arm, fingertip or hand. Without it, every part of the scene, each a node
    /// in its default namespace (`/hand0`, `/pad0`, `/arm0`), in this one process.
    #[arg(long)]
    pub part: Option<Part>,
    /// The part's namespace (default: the part's, e.g. `/arm0`).
    #[arg(long, requires = "part")]
    pub namespace: Option<String>,
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
    /// The joining options of `part`'s node.
    pub fn args(&self, part: Part) -> NodeArgs {
        NodeArgs {
            part,
            namespace: self
                .namespace
                .clone()
                .unwrap_or_else(|| part.default_namespace().to_owned()),
            connect: self.connect.clone(),
            domain_id: self.domain,
            humble: self.humble,
        }
    }

    /// Runs the named part, or every part `scene_parts` gives, each with `run` on its own
    /// thread until stdin closes or a signal (SIGINT, SIGTERM, SIGHUP) stops it; prints what
    /// each did on stderr. A part that fails stops the others (each ends through its end
    /// action or stop) and the exit status says so: the failure's (as `handstack run`'s), else
    /// 128 + the signal's number, else 0.
    pub fn main(
        &self,
        scene_parts: impl FnOnce() -> Result<Vec<Part>, CellError>,
        run: impl Fn(&NodeArgs, &Stop) -> Result<String, CellError> + Sync,
    ) -> std::process::ExitCode {
        let stop = crate::stop::signal_stop();
        stop.on_stdin_eof();
        let parts = match self.part {
            Some(p) => vec![p],
            None => match scene_parts() {
                Ok(parts) if !parts.is_empty() => parts,
                Ok(_) => {
                    eprintln!("error: {}: no part to run as a node", self.scene.display());
                    return std::process::ExitCode::FAILURE;
                }
                Err(e) => {
                    eprintln!("error: {}: {e}", self.scene.display());
                    return std::process::ExitCode::FAILURE;
                }
            },
        };
        let failed: Option<u8> = std::thread::scope(|scope| {
            let handles: Vec<_> = parts
                .iter()
                .map(|&part| {
                    let (args, stop, run) = (self.args(part), &stop, &run);
                    scope.spawn(move || {
                        let result = run(&args, stop);
                        if result.is_err() {
                            stop.set();
                        }
                        (args, result)
                    })
                })
                .collect();
            let mut failed = None;
            for h in handles {
                match h.join() {
                    Ok((args, Ok(done))) => {
                        eprintln!("{} {}: {done}", args.namespace, args.part.as_str())
                    }
                    Ok((args, Err(e))) => {
                        eprintln!("error: {} {}: {e}", args.namespace, args.part.as_str());
                        failed = failed.or(Some(e.exit_code()));
                    }
                    Err(_) => {
                        stop.set();
                        failed = failed.or(Some(crate::error::EXIT_FAULT));
                    }
                }
            }
            failed
        });
        let code = match (failed, stop.reason()) {
            (Some(code), _) => code,
            (None, Some(r @ StopReason::Signal(_))) => r.exit_code(),
            (None, _) => 0,
        };
        std::process::ExitCode::from(code)
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
        let stop = crate::stop::signal_stop();
        let runs = crate::summary::run_each(&self.cells, self.json, &bars, &stop, |path| {
            let taps = super::file::CellFile::load(path)?
                .coordinator
                .tap_to_move
                .taps;
            bars.stage("cell: pad node → coordinator → arm node", taps as u64);
            let run = launch::run(path, &program, &stop, |_| bars.advance(1))?;
            Ok::<_, CellError>(outcome(path, &run))
        });
        std::process::ExitCode::from(runs.exit_code)
    }
}

impl crate::summary::ExitStatus for CellError {
    fn exit_code(&self) -> u8 {
        CellError::exit_code(self)
    }
}
