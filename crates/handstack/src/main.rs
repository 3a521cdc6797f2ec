//! `handstack`: run scene files (`handstack run SCENE... [--json]`), train the committed models
//! (`handstack train MODEL`), measure the speed / accuracy trade (`handstack trade`).

use clap::{Parser, Subcommand};
use handstack::progress::{Progress, Quiet};
use handstack::runs::RunContext;
use indicatif::{ProgressBar, ProgressStyle};
use std::io::IsTerminal as _;
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
    /// Build the stack each scene file names and run its experiments.
    Run {
        /// Scene files (fixtures/scenes/*.toml).
        #[arg(required = true)]
        scenes: Vec<PathBuf>,
        /// Print the outcomes as JSON on stdout (no progress, no table).
        #[arg(long)]
        json: bool,
        /// Also write the HTML report of the outcomes (and docs/trade/points.csv) here.
        #[arg(long, value_name = "PATH")]
        report: Option<PathBuf>,
    },
    /// Train one committed model family and write its weights and metrics.
    Train {
        /// contact-mlp | force-dnn | softness | contact-cnn
        model: String,
        /// Workspace root (default: the nearest directory holding fixtures/models).
        #[arg(long)]
        root: Option<PathBuf>,
        /// contact-mlp, contact-cnn: quick run at this many epochs (writes nothing).
        #[arg(long)]
        epochs: Option<usize>,
        /// contact-cnn: only protocol rows starting with this label (writes nothing);
        /// softness: only optimiser 0 (LM) or 1 (Adam).
        #[arg(long)]
        only: Option<String>,
        /// softness: train and report, write nothing.
        #[arg(long)]
        dry_run: bool,
    },
    /// Measure cost against accuracy for every knob; write docs/trade.md and docs/trade/.
    Trade {
        /// Workspace root (default: the nearest directory holding fixtures/models).
        #[arg(long)]
        root: Option<PathBuf>,
    },
}

/// A progress bar per stage on stderr.
struct Bars(ProgressBar);

impl Progress for Bars {
    fn stage(&self, name: &str, len: u64) {
        self.0.set_length(len);
        self.0.set_position(0);
        self.0.set_message(name.to_owned());
    }
    fn advance(&self, n: u64) {
        self.0.inc(n);
    }
}

fn main() -> ExitCode {
    match Cli::parse().command {
        Command::Run {
            scenes,
            json,
            report: html,
        } => run(&scenes, json, html.as_deref()),
        Command::Train {
            model,
            root,
            epochs,
            only,
            dry_run,
        } => report(train(&model, root, epochs, only, dry_run)),
        Command::Trade { root } => report(trade(root)),
    }
}

fn run(scenes: &[PathBuf], json: bool, report: Option<&std::path::Path>) -> ExitCode {
    let live = !json && std::io::stderr().is_terminal();
    let bars = Bars(if live {
        let bar = ProgressBar::new(0).with_style(
            ProgressStyle::with_template(
                "{spinner} {prefix} {msg} [{bar:30}] {pos}/{len} {elapsed}",
            )
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
        );
        bar.enable_steady_tick(std::time::Duration::from_millis(200));
        bar
    } else {
        ProgressBar::hidden()
    });
    let quiet = Quiet;
    let progress: &dyn Progress = if live { &bars } else { &quiet };
    let cx = RunContext::new(progress);
    let (mut outcomes, mut failed) = (Vec::new(), false);
    let mut failures = Vec::new();
    for path in scenes {
        bars.0.set_prefix(path.display().to_string());
        match handstack::run_file(path, &cx) {
            Ok(o) => {
                if !json {
                    bars.0
                        .suspend(|| println!("{}", handstack::summary::table(&o)));
                }
                outcomes.push(o);
            }
            Err(e) => {
                bars.0
                    .suspend(|| eprintln!("error: {}: {e}", path.display()));
                failed = true;
                failures.push(handstack::report::Failed {
                    scene: path.display().to_string(),
                    error: e.to_string(),
                });
            }
        }
    }
    bars.0.finish_and_clear();
    if json {
        match serde_json::to_string_pretty(&outcomes) {
            Ok(s) => println!("{s}"),
            Err(e) => {
                eprintln!("error: cannot write JSON: {e}");
                failed = true;
            }
        }
    }
    if let Some(out) = report {
        let points = cx.root.join(handstack::report::TRADE_POINTS);
        match handstack::report::write_html(&outcomes, &failures, Some(&points), out) {
            Ok(()) => eprintln!("report: {}", out.display()),
            Err(e) => {
                eprintln!("error: report: {e}");
                failed = true;
            }
        }
    }
    if failed {
        ExitCode::FAILURE
    } else {
        ExitCode::SUCCESS
    }
}

/// Prints `result`'s error, if any, as the exit status says.
fn report(result: Result<(), String>) -> ExitCode {
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}

/// `root`, or the nearest directory at or above the current one holding fixtures/models.
fn workspace(root: Option<PathBuf>) -> Result<PathBuf, String> {
    root.or_else(|| {
        std::env::current_dir()
            .ok()
            .and_then(|d| handstack::train::find_root(&d))
    })
    .ok_or_else(|| "no fixtures/models here or above: pass --root".into())
}

fn train(
    model: &str,
    root: Option<PathBuf>,
    epochs: Option<usize>,
    only: Option<String>,
    dry_run: bool,
) -> Result<(), String> {
    let model = handstack::train::Model::from_name(model).map_err(|e| e.to_string())?;
    let options = handstack::train::TrainOptions {
        epochs,
        only,
        dry_run,
    };
    let written =
        handstack::train::run(&workspace(root)?, model, &options).map_err(|e| e.to_string())?;
    for path in written {
        println!("wrote {}", path.display());
    }
    Ok(())
}

fn trade(root: Option<PathBuf>) -> Result<(), String> {
    let root = workspace(root)?;
    let trade = handstack::trade::run(&root, |step| eprintln!("trade: {step}"))
        .map_err(|e| e.to_string())?;
    for file in handstack::trade::write(&root, &trade).map_err(|e| e.to_string())? {
        println!("wrote {file}");
    }
    println!("trade run: {:.1} s", trade.wall_s);
    Ok(())
}
