//! `handstack`: run scene files (`handstack run SCENE... [--json] [--report PATH]`). Training
//! the committed models and the speed / accuracy trade are the reproduction's (`papers train
//! MODEL`, `papers trade`).

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
