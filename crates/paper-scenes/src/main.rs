//! `paper-scenes`: run the papers' scene files (`paper-scenes run SCENE... [--json] [--report
//! PATH]`) on the handstack stack, simulated devices behind the real interfaces. Training the
//! committed models and the speed / accuracy trade are `papers train MODEL` and `papers trade`.

use clap::{Parser, Subcommand};
use handstack::progress::Bars;
use paper_scenes::runs::RunContext;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// The papers' scenes on the handstack stack.
#[derive(Parser)]
#[command(name = "paper-scenes", version, about)]
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
        /// Also write the HTML report of the outcomes here.
        #[arg(long, value_name = "PATH")]
        report: Option<PathBuf>,
    },
    /// Run a scene's stack (or one part: pad, arm, fingertip or hand) on its simulated devices
    /// as ROS 2 nodes on Zenoh, until stdin closes.
    #[cfg(feature = "cell")]
    Node {
        #[command(flatten)]
        node: handstack::cell::cli::NodeCommand,
        /// Read the simulated device this many times faster than real time.
        #[arg(long, default_value_t = 1.0)]
        sim_speed: f64,
    },
    /// Start a Zenoh router, the nodes a cell file names (each a `paper-scenes node` process)
    /// and the coordinator of seed 002's tap-to-move across them.
    #[cfg(feature = "cell")]
    Cell(handstack::cell::cli::CellCommand),
}

fn main() -> ExitCode {
    match Cli::parse().command {
        Command::Run {
            scenes,
            json,
            report,
        } => run(&scenes, json, report.as_deref()),
        #[cfg(feature = "cell")]
        Command::Node { node, sim_speed } => node.main(
            || {
                let scene = paper_scenes::scene::PaperScene::load(&node.scene)?;
                Ok(handstack::cell::scene_parts(&scene))
            },
            |args, stop| {
                let scene = paper_scenes::scene::PaperScene::load(&node.scene)?;
                let progress = handstack::progress::Quiet;
                let cx = RunContext::new(&progress);
                paper_scenes::cell::run_node(&scene, args, sim_speed, &cx, stop)
            },
        ),
        #[cfg(feature = "cell")]
        Command::Cell(cmd) => cmd.main(paper_scenes::cell::outcome),
    }
}

fn run(scenes: &[PathBuf], json: bool, report: Option<&Path>) -> ExitCode {
    let bars = Bars::new(!json);
    let mut cx = RunContext::new(&bars);
    cx.stack.stop = handstack::stop::signal_stop();
    let runs = handstack::summary::run_each(scenes, json, &bars, &cx.stop, |path| {
        paper_scenes::run_file(path, &cx)
    });
    let mut code = runs.exit_code;
    if let Some(out) = report {
        let failures: Vec<_> = runs
            .failures
            .into_iter()
            .map(|(scene, error)| paper_scenes::report::Failed { scene, error })
            .collect();
        let points = cx.root.join(paper_scenes::report::TRADE_POINTS);
        match paper_scenes::report::write_html(&runs.outcomes, &failures, Some(&points), out) {
            Ok(()) => eprintln!("report: {}", out.display()),
            Err(e) => {
                eprintln!("error: report: {e}");
                code = code.max(1);
            }
        }
    }
    ExitCode::from(code)
}
