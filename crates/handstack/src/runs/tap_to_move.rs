//! Tap-to-move (Al & Martinez-Hernandez, §IV-B) on the user's own pad and arm: for
//! each region the scene lists, the run asks for a tap there, waits for it, locates it with the
//! built-in contact CNN (the paper's variant) from the accelerometer / gyroscope window around
//! the trigger, and moves the arm from home to the region's grid pose ([`crate::tap_to_move`],
//! the loop the cell runs across processes). The pad is read at its frame rate (30 Hz, the
//! CNN's), and each window resampled to it ([`at_rate`]) when the line is slower. After the last tap the arm goes home; a stop (a signal), a fault or a tap that never
//! comes stops it where it is (a move under way ends first: the stop is seen at the next frame).

use super::figure::{Target, measured, target};
use super::{Part, RunContext};
use crate::error::{Ending, RunError};
use crate::pace::Pacer;
use crate::scene::Scene;
use crate::scene::experiment::TapToMove as TapScene;
use crate::stack::pad::FRAME_RATE_HZ;
use crate::stop::{Stop, StopReason};
use crate::tap_to_move::{ExperimentError, RegionToGrid, TapToMove, TapToMoveConfig, at_rate};
use crate::{Line, Plot};
use hand_traits::{Arm, ImuFrame, TactileSource};
use tactile_nets::contact_cnn::{self, Variant};

/// The accuracy of the paper's real-time test, %: the target of a run (§IV-B).
const PAPER_ACCURACY_PCT: f64 = 93.0;

/// Why the pad gave no frame: the run's stop, or the pad's own error.
#[derive(Debug)]
enum PadEnd {
    Stopped(StopReason),
    Pad(RunError),
}

impl core::fmt::Display for PadEnd {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            PadEnd::Stopped(r) => write!(f, "stopped by {r}"),
            PadEnd::Pad(e) => e.fmt(f),
        }
    }
}

/// The pad read at its frame rate until the run's stop.
struct Paced<'a, S> {
    pad: &'a mut S,
    pacer: Pacer,
    stop: &'a Stop,
}

impl<S: TactileSource<Frame = ImuFrame, Error = RunError>> TactileSource for Paced<'_, S> {
    type Frame = ImuFrame;
    type Error = PadEnd;

    fn read_frame(&mut self) -> Result<ImuFrame, PadEnd> {
        if let Some(r) = self.stop.reason() {
            return Err(PadEnd::Stopped(r));
        }
        self.pacer.wait();
        self.pad.read_frame().map_err(PadEnd::Pad)
    }
}

/// Runs `[experiment.tap_to_move]` of `scene` on its real pad and arm.
pub fn run(scene: &Scene, exp: &TapScene, cx: &RunContext<'_>) -> Result<Part, RunError> {
    let host = scene
        .file
        .arm
        .as_ref()
        .and_then(|a| a.get_ref().host.as_ref())
        .map(|h| h.get_ref().clone())
        .ok_or_else(|| device("arm", "names no host"))?;
    let mut source = crate::stack::pad::open_scene(scene, &*cx.platform)?;
    let mut arm = cx.arm(&host)?;
    let mut cnn = tactile_nets::pretrained::contact_cnn(Variant::Paper)
        .map_err(|e| device("estimators.contact", format!("the contact CNN: {e}")))?;
    let mut config = cnn.trigger_offset().map_or_else(
        TapToMoveConfig::default,
        TapToMoveConfig::centred_after_trigger,
    );
    config.max_wait_frames = (exp.wait_s() * FRAME_RATE_HZ).ceil() as usize;
    let grid =
        RegionToGrid::ur3_default().map_err(|e| device("arm", format!("the UR3 grid: {e}")))?;
    let mut taps = TapToMove::new(&grid, config);
    let mut paced = Paced {
        pad: &mut source,
        pacer: Pacer::new(FRAME_RATE_HZ),
        stop: &cx.stop,
    };
    let regions = exp.regions();
    let n = regions.len();
    cx.progress.stage("tap-to-move: taps", n as u64);
    let mut rows = Vec::with_capacity(n);
    for (i, &asked) in regions.iter().enumerate() {
        cx.progress.say(&format!(
            "Tap region {asked} of the pad (column {}, row {}), tap {} of {n}.",
            asked % 3 + 1,
            asked / 3 + 1,
            i + 1
        ));
        // The pacer's first tick counts from now: the question may have waited.
        paced.pacer = Pacer::new(FRAME_RATE_HZ);
        let report = taps
            .cycle(&mut paced, &mut cnn, &mut arm, |frames| {
                // At the CNN's 30 Hz, whatever rate the line allowed.
                let frames = at_rate(frames, config.frames_before, FRAME_RATE_HZ);
                contact_cnn::window(&frames).unwrap_or([f32::NAN; contact_cnn::WINDOW_VALUES])
            })
            .map_err(|e| ended(e, i + 1, n, &host, exp.wait_s()))?;
        cx.progress.say(&format!(
            "  located region {} ({:.0} % sure){}",
            report.region,
            100.0 * report.confidence,
            if report.in_range {
                format!(", the arm moved there in {:.2} s", report.move_s)
            } else {
                ": outside the CNN's training range, the arm stays home".to_owned()
            }
        ));
        cx.progress.advance(1);
        rows.push((asked, report));
    }
    // The end of the list: the arm goes home, where each tap started.
    if let Err(e) = arm.move_linear(grid.home(), &config.motion) {
        let _ = arm.stop();
        return Err(RunError::Ended {
            ending: Ending::Fault,
            what: format!(
                "tap-to-move: the move home after the last tap: {e}; arm at {host} told to stop"
            ),
        });
    }
    let mut part = part(&rows, &host);
    part.notes
        .push(format!("arm at {host}: home after {n} taps"));
    Ok(part)
}

fn device(device: &'static str, reason: impl Into<String>) -> RunError {
    RunError::Device {
        device,
        reason: reason.into(),
    }
}

/// A cycle's error as the run's ending (the loop stopped the arm first).
fn ended<A: core::fmt::Display + core::fmt::Debug>(
    e: ExperimentError<PadEnd, tactile_nets::error::NetError, A>,
    i: usize,
    n: usize,
    host: &str,
    wait_s: f64,
) -> RunError {
    let at = format!("at tap {i} of {n}; arm at {host} told to stop");
    match e {
        ExperimentError::Source(PadEnd::Stopped(r)) => RunError::Ended {
            ending: Ending::Stopped(r),
            what: format!("tap-to-move: stopped by {r} {at}"),
        },
        ExperimentError::NoContact(_) => RunError::Ended {
            ending: Ending::Failed,
            what: format!("tap-to-move: no tap within {wait_s} s {at}"),
        },
        other => RunError::Ended {
            ending: Ending::Fault,
            what: format!("tap-to-move: {other} {at}"),
        },
    }
}

/// The taps' figures and plot: `rows` of (region asked, what the cycle did).
fn part(rows: &[(u8, crate::tap_to_move::CycleReport)], host: &str) -> Part {
    let mut part = Part::default();
    let n = rows.len().max(1) as f64;
    let hits = rows
        .iter()
        .filter(|(asked, r)| u16::from(*asked) == r.region)
        .count();
    part.figures
        .push(measured("taps", "taps located", rows.len() as f64, ""));
    let f = measured(
        "tap_accuracy_pct",
        &format!("CNN region accuracy, {} taps (arm at {host})", rows.len()),
        100.0 * hits as f64 / n,
        "%",
    );
    let f = super::figure::paper(
        f,
        PAPER_ACCURACY_PCT,
        "Al & Martinez-Hernandez, §IV-B (real-time test)",
    );
    part.figures
        .push(target(f, Target::AtLeast(PAPER_ACCURACY_PCT)));
    part.figures.push(measured(
        "outside_range",
        "taps outside the CNN's training range (arm not moved)",
        rows.iter().filter(|(_, r)| !r.in_range).count() as f64,
        "",
    ));
    let moves: Vec<f64> = rows
        .iter()
        .filter(|(_, r)| r.in_range)
        .map(|(_, r)| r.move_s)
        .collect();
    part.figures.push(measured(
        "move_mean_s",
        "move to the grid pose, mean (wall)",
        moves.iter().sum::<f64>() / moves.len().max(1) as f64,
        "s",
    ));
    part.figures.push(measured(
        "locate_mean_ms",
        "CNN locate, mean (wall)",
        1e3 * rows.iter().map(|(_, r)| r.locate_s).sum::<f64>() / n,
        "ms",
    ));
    part.plots.push(Plot::Lines {
        title: "Taps: region located against region asked".into(),
        x_label: "tap".into(),
        y_label: "region".into(),
        lines: vec![
            Line {
                label: "asked".into(),
                points: (0..rows.len())
                    .map(|i| (i as f64 + 1.0, f64::from(rows[i].0)))
                    .collect(),
            },
            Line {
                label: "located".into(),
                points: (0..rows.len())
                    .map(|i| (i as f64 + 1.0, f64::from(rows[i].1.region)))
                    .collect(),
            },
        ],
    });
    part
}
