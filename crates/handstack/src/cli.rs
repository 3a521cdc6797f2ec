//! The `handstack` command line: run a tactile hand stack from a scene file on its real devices
//! (`handstack run SCENE... [--json]`), or only check scene files (`handstack check SCENE...`);
//! record guided sessions to train on (`handstack collect SCENE --into DIR`); zero the
//! underactuated hand's potentiometers (`handstack calibrate SCENE`). With feature
//! `train`: a model of the user's own from those sessions (`handstack train
//! force|contact-mlp|contact-cnn|softness DIR --out FILE`). With feature `cell`: a scene's stack as ROS 2 nodes on Zenoh (`handstack node SCENE`, or one
//! part: `--part P [--namespace NS]`), and a cell of such nodes with a coordinator (`handstack
//! cell CELL.toml`).
//!
//! [`main`] is the whole program; the `handstack` binary calls it with Linux's device files.
//! A program for a board reached another way (a USB–I2C bridge, a bench without a fingertip)
//! calls it with its own [`Platform`], and gets the same command line, the same shutdown on
//! every signal and the same exit statuses.

use crate::progress::Bars;
use crate::record::Recorder;
use crate::runs::RunContext;
#[cfg(feature = "cell")]
use crate::scene::NodeScene;
use crate::scene::{ExperimentTable as _, Scene};
use crate::stack::platform::Platform;
use clap::{Parser, Subcommand};
use std::path::PathBuf;
use std::process::ExitCode;

/// Makes the platform a run opens its hardware through (one per run, or per node part).
pub type Platforms<'a> = &'a (dyn Fn() -> Box<dyn Platform> + Sync);

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
        /// Record the run into this directory as a ROS 2 bag (rosbag2, MCAP storage): every
        /// frame, estimate, command, fault and figure, as it happens. The directory must be new
        /// or empty.
        #[arg(long, value_name = "DIR")]
        record: Option<PathBuf>,
    },
    /// Collect the data to train your own models: the scene's experiment asks what to do
    /// next, as a run does, and records the frames and what you did into a new session bag
    /// in DIR. Run it again with the same DIR to go on where the last session stopped.
    Collect {
        /// The scene file: its `[experiment.weight]` lists the weights to collect, its
        /// `[experiment.contact]` the fingertip's cells to tap, its `[experiment.tap_to_move]`
        /// the pad's regions to tap, or its `[experiment.softness]` the `objects` to grasp.
        scene: PathBuf,
        /// The collect directory: one bag per session (`session-001`, …).
        #[arg(long, value_name = "DIR")]
        into: PathBuf,
        /// Print the outcome as JSON on stdout (no progress, no table).
        #[arg(long)]
        json: bool,
    },
    /// Zero the underactuated hand's potentiometers on the hand itself: with the hand open and
    /// empty, read each distal angle and give the `[sensors.underactuated] pot` line that reads
    /// the open joints as 0°. The stepper is not moved.
    Calibrate {
        /// The scene file naming the hand (`[hand] model = "underactuated4"`).
        scene: PathBuf,
        /// Print the outcome as JSON on stdout (no progress, no table).
        #[arg(long)]
        json: bool,
    },
    /// Train a model of your own from collect sessions and write its weights file, which a
    /// scene then names.
    #[cfg(feature = "train")]
    Train(crate::train::TrainCommand),
    /// Parse and validate scene files without opening anything.
    Check {
        /// Scene files.
        #[arg(required = true)]
        scenes: Vec<PathBuf>,
    },
    /// Run a scene's stack (or one part: pad, arm, fingertip or hand) on its real devices as
    /// ROS 2 nodes on Zenoh (rmw_zenoh's conventions), until stdin closes.
    #[cfg(feature = "cell")]
    Node(crate::cell::cli::NodeCommand),
    /// Start a Zenoh router, the nodes a cell file names (each its own process) and the
    /// coordinator of tap-to-move across them (Al & Martinez-Hernandez, §IV-B).
    #[cfg(feature = "cell")]
    Cell(crate::cell::cli::CellCommand),
}

/// Parses the command line and runs it, opening hardware through `platforms`.
pub fn main(platforms: Platforms<'_>) -> ExitCode {
    match Cli::parse().command {
        Command::Run {
            scenes,
            json,
            record,
        } => {
            // The bag is made before any scene is opened: a directory it cannot use stops the
            // run before anything moves.
            match record.as_deref().map(Recorder::create).transpose() {
                Ok(recorder) => run(&scenes, json, recorder, None, platforms),
                Err(e) => not_started(&e),
            }
        }
        Command::Collect { scene, into, json } => collect(scene, &into, json, platforms),
        Command::Calibrate { scene, json } => calibrate(&scene, json),
        #[cfg(feature = "train")]
        Command::Train(cmd) => cmd.main(),
        Command::Check { scenes } => check(&scenes),
        #[cfg(feature = "cell")]
        Command::Node(cmd) => cmd.main(
            || Ok(crate::cell::scene_parts(&NodeScene::load(&cmd.scene)?)),
            |args, stop| {
                let scene = NodeScene::load(&cmd.scene)?;
                crate::cell::real::run_node(&scene, args, stop, &*platforms())
            },
        ),
        #[cfg(feature = "cell")]
        Command::Cell(cmd) => cmd.main(|path, run| {
            let name = path.file_stem().unwrap_or_default().to_string_lossy();
            crate::cell::outcome::outcome(&name, run)
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

/// Prints `e` and gives the status of a run that did not start.
fn not_started(e: &dyn std::fmt::Display) -> ExitCode {
    eprintln!("error: {e}");
    ExitCode::from(crate::error::EXIT_NOT_STARTED)
}

/// `handstack collect SCENE --into DIR`: a new session bag in DIR for what the sessions before
/// it have not recorded.
fn collect(
    scene: PathBuf,
    into: &std::path::Path,
    json: bool,
    platforms: Platforms<'_>,
) -> ExitCode {
    let loaded = match Scene::load(&scene) {
        Ok(s) => s,
        Err(e) => return not_started(&e),
    };
    let x = loaded.file.experiment.get_ref();
    let names = x.names();
    // What the session collects, and the command that trains on it.
    let train = match (&x.weight, &x.tap_to_move, &x.softness, &x.contact) {
        _ if names.len() != 1 => None,
        (Some(_), ..) => Some("force"),
        (_, Some(_), ..) => Some("contact-cnn"),
        (_, _, Some(s), _) if !s.get_ref().objects().is_empty() => Some("softness"),
        (.., Some(_)) => Some("contact-mlp"),
        _ => None,
    };
    let Some(train) = train else {
        return not_started(&format!(
            "{}: `handstack collect` records one experiment's training data, \
             [experiment.weight] (the force DNN's), [experiment.contact] (the contact \
             MLP's), [experiment.tap_to_move] (the contact CNN's) or [experiment.softness] \
             with `objects` (the softness net's); the scene runs {}",
            scene.display(),
            names.join(", ")
        ));
    };
    let sessions = match crate::collect::Sessions::open(into) {
        Ok(s) => s,
        Err(e) => return not_started(&e),
    };
    let left = match (&x.weight, &x.tap_to_move, &x.softness, &x.contact) {
        (Some(w), ..) => crate::runs::weight::to_collect(&w.get_ref().plan(), &sessions)
            .weights_gf
            .len(),
        (_, Some(t), ..) => {
            crate::runs::tap_to_move::to_collect(&t.get_ref().regions(), &sessions).len()
        }
        (_, _, Some(s), _) => {
            crate::runs::softness::to_collect(&s.get_ref().objects(), &sessions).len()
        }
        (.., Some(c)) => crate::runs::contact::to_collect(&c.get_ref().cells(), &sessions).len(),
        _ => 0,
    };
    if left == 0 {
        eprintln!(
            "everything {} asks for is recorded in {} ({} sessions): train with `handstack \
             train {train} {} --out FILE`",
            scene.display(),
            into.display(),
            sessions.count(),
            into.display()
        );
        return ExitCode::SUCCESS;
    }
    match Recorder::create(&sessions.next_session()) {
        Ok(recorder) => run(&[scene], json, Some(recorder), Some(sessions), platforms),
        Err(e) => not_started(&e),
    }
}

/// `handstack calibrate SCENE`: the hand's potentiometers zeroed, printed as a scene line.
fn calibrate(path: &std::path::Path, json: bool) -> ExitCode {
    let scene = match Scene::load(path) {
        Ok(s) => s,
        Err(e) => return not_started(&e),
    };
    if scene.file.underactuated_hand().is_none() {
        return not_started(&format!(
            "{}: `handstack calibrate` zeroes the underactuated hand's potentiometers, and the \
             scene names no such hand ([hand] model = \"underactuated4\")",
            path.display()
        ));
    }
    let bars = Bars::new(!json);
    let cx = RunContext::new(&bars).with_stop(crate::stop::signal_stop());
    match crate::calibrate::calibrate(&scene, &cx) {
        Ok(outcome) => {
            crate::summary::print(&outcome, json);
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("error: {}: {e}", path.display());
            ExitCode::from(crate::summary::ExitStatus::exit_code(&e))
        }
    }
}

/// Runs `scenes`, recording into `recorder` if given; collecting after `sessions` if given.
fn run(
    scenes: &[PathBuf],
    json: bool,
    recorder: Option<Recorder>,
    sessions: Option<crate::collect::Sessions>,
    platforms: Platforms<'_>,
) -> ExitCode {
    let bars = Bars::new(!json);
    let mut cx = RunContext::new(&bars).with_stop(crate::stop::signal_stop());
    match (&recorder, sessions) {
        (Some(r), Some(s)) => cx = cx.with_collect(r, s),
        (Some(r), None) => cx = cx.with_record(r),
        _ => {}
    }
    cx.platform = platforms();
    let runs = crate::summary::run_each(scenes, json, &bars, &cx.stop, |path| {
        crate::run_file(path, &cx)
    });
    let mut code = runs.exit_code;
    if let Some(r) = &recorder {
        match r.finish() {
            Ok(n) => eprintln!("recorded {n} messages to {}", r.dir().display()),
            Err(e) => {
                eprintln!("error: {e}");
                if code == 0 {
                    code = crate::error::EXIT_FAULT;
                }
            }
        }
    }
    ExitCode::from(code)
}

fn exit(failed: bool) -> ExitCode {
    if failed {
        ExitCode::FAILURE
    } else {
        ExitCode::SUCCESS
    }
}
