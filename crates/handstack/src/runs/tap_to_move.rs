//! Tap-to-move (Al & Martinez-Hernandez, §IV-B) on the user's own pad and arm: for
//! each region the scene lists, the run asks for a tap there, waits for it, locates it with the
//! scene's contact CNN (the user's own weights file, or the built-in paper variant) from the
//! accelerometer / gyroscope window around the trigger, and moves the arm from home to the
//! region's grid pose ([`crate::tap_to_move`], the loop the cell runs across processes). The pad
//! is read at its frame rate (30 Hz, the CNN's), and each window resampled to it ([`at_rate`])
//! when the line is slower. After the last tap the arm goes home; a stop (a signal), a fault or
//! a tap that never comes stops it where it is (a move under way ends first: the stop is seen
//! at the next frame).
//!
//! Collecting (`handstack collect`), the same questions record the training data of the user's
//! own contact CNN instead: every pad frame, and a label of the region asked over each tap's
//! window (cut as the run cuts it); the arm is neither connected nor moved. A later session asks
//! only for the taps no earlier one recorded (each region as many times as the scene lists it).

use super::figure::{Target, measured, target};
use super::{Part, RunContext};
use crate::collect::Sessions;
use crate::error::{Ending, RunError};
use crate::pace::Pacer;
use crate::record::pad::{ImuTopic, PAD_FRAME};
use crate::record::{Labelled, Recorder, now_ns};
use crate::scene::Scene;
use crate::scene::experiment::TapToMove as TapScene;
use crate::stack::pad::FRAME_RATE_HZ;
use crate::stop::{Stop, StopReason};
use crate::tap_to_move::{
    ExperimentError, RegionToGrid, TapToMove, TapToMoveConfig, TapTrigger, at_rate,
};
use crate::{Line, Plot};
use hand_traits::{Arm, ImuFrame, TactileSource};
use std::collections::VecDeque;
use tactile_nets::contact_cnn::{self, ContactCnn};

/// The accuracy of the paper's real-time test, %: the target of a run (§IV-B).
pub(crate) const PAPER_ACCURACY_PCT: f64 = 93.0;
/// Where [`PAPER_ACCURACY_PCT`] comes from.
pub(crate) const PAPER_SOURCE: &str = "Al & Martinez-Hernandez, §IV-B (real-time test)";

/// The experiment's name in a collect session's labels.
pub const EXPERIMENT: &str = "tap_to_move";
/// The label of a tap's window, its value the region asked for (0…8).
pub const REGION: &str = "region";
/// Frames whose read time a collect session keeps, to stamp a window's first and last.
const STAMPS_KEPT: usize = 256;

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

/// The pad read at its frame rate until the run's stop, each frame recorded when the run is.
struct Paced<'a, S> {
    pad: &'a mut S,
    pacer: Pacer,
    stop: &'a Stop,
    imu: Option<ImuTopic<'a>>,
    /// The last frames' source times (µs) and read times (ns since the Unix epoch).
    stamps: VecDeque<(u64, u64)>,
}

impl<'a, S> Paced<'a, S> {
    fn new(pad: &'a mut S, stop: &'a Stop, record: Option<&'a Recorder>) -> Self {
        Paced {
            pad,
            pacer: Pacer::new(FRAME_RATE_HZ),
            stop,
            imu: record.map(ImuTopic::new),
            stamps: VecDeque::with_capacity(STAMPS_KEPT),
        }
    }

    /// The read time (the bag's) of the frame of source time `t_us`, if kept.
    fn stamp_of(&self, t_us: u64) -> Option<u64> {
        self.stamps
            .iter()
            .find(|(t, _)| *t == t_us)
            .map(|&(_, ns)| ns)
    }
}

impl<S: TactileSource<Frame = ImuFrame, Error = RunError>> TactileSource for Paced<'_, S> {
    type Frame = ImuFrame;
    type Error = PadEnd;

    fn read_frame(&mut self) -> Result<ImuFrame, PadEnd> {
        if let Some(r) = self.stop.reason() {
            return Err(PadEnd::Stopped(r));
        }
        self.pacer.wait();
        let f = self.pad.read_frame().map_err(PadEnd::Pad)?;
        let t_ns = now_ns();
        if let Some(imu) = &mut self.imu {
            imu.record(t_ns, &f);
        }
        if self.stamps.len() == STAMPS_KEPT {
            self.stamps.pop_front();
        }
        self.stamps.push_back((f.t_us, t_ns));
        Ok(f)
    }
}

/// Asks for tap `i` (from 0) of `n`, on `region`; the pad's frames are paced from now (the
/// question may have waited).
fn ask<S>(cx: &RunContext<'_>, paced: &mut Paced<'_, S>, region: u8, i: usize, n: usize) {
    cx.progress.say(&format!(
        "Tap region {region} of the pad (column {}, row {}), tap {} of {n}.",
        region % 3 + 1,
        region / 3 + 1,
        i + 1
    ));
    paced.pacer = Pacer::new(FRAME_RATE_HZ);
}

/// The trigger and window `cnn` was trained on: centred where its training windows sat after
/// the trigger, the paper's §IV-A window when the model does not say.
pub fn window_config(cnn: &ContactCnn) -> TapToMoveConfig {
    cnn.trigger_offset().map_or_else(
        TapToMoveConfig::default,
        TapToMoveConfig::centred_after_trigger,
    )
}

/// Runs `[experiment.tap_to_move]` of `scene` on its real pad and arm, or, in a collect
/// session ([`RunContext::collect`]), records the taps still to collect.
pub fn run(scene: &Scene, exp: &TapScene, cx: &RunContext<'_>) -> Result<Part, RunError> {
    if let (Some(sessions), Some(recorder)) = (&cx.collect, cx.record) {
        return collect(scene, exp, sessions, recorder, cx);
    }
    let host = scene
        .file
        .arm
        .as_ref()
        .and_then(|a| a.get_ref().host.as_ref())
        .map(|h| h.get_ref().clone())
        .ok_or_else(|| device("arm", "names no host"))?;
    let mut source = crate::stack::pad::open_scene(scene, &*cx.platform)?;
    let mut arm = cx.arm(&host)?;
    let mut cnn = scene
        .contact_cnn()
        .map_err(|e| device("estimators.contact", format!("the contact CNN: {e}")))?;
    let mut config = window_config(&cnn);
    config.max_wait_frames = (exp.wait_s() * FRAME_RATE_HZ).ceil() as usize;
    let grid =
        RegionToGrid::ur3_default().map_err(|e| device("arm", format!("the UR3 grid: {e}")))?;
    let mut taps = TapToMove::new(&grid, config);
    let mut paced = Paced::new(&mut source, &cx.stop, cx.record);
    let regions = exp.regions();
    let n = regions.len();
    cx.progress.stage("tap-to-move: taps", n as u64);
    let mut rows = Vec::with_capacity(n);
    for (i, &asked) in regions.iter().enumerate() {
        ask(cx, &mut paced, asked, i, n);
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

/// The taps of `regions` without those `sessions` recorded already: each region as many times
/// as `regions` lists it, less the times it was recorded.
pub fn to_collect(regions: &[u8], sessions: &Sessions) -> Vec<u8> {
    sessions.left(regions, EXPERIMENT, REGION, f64::from)
}

/// The collect session: each tap still to collect asked for, its window found by the run's
/// trigger, labelled in `recorder` with the region asked over the window's first and last
/// frame; every frame recorded.
fn collect(
    scene: &Scene,
    exp: &TapScene,
    sessions: &Sessions,
    recorder: &Recorder,
    cx: &RunContext<'_>,
) -> Result<Part, RunError> {
    let regions = to_collect(&exp.regions(), sessions);
    let n = regions.len();
    // Windows cut as the built-in CNN's were: the run with the trained model cuts them so too.
    let cnn = tactile_nets::pretrained::contact_cnn(contact_cnn::Variant::Paper)
        .map_err(|e| device("estimators.contact", format!("the contact CNN: {e}")))?;
    let config = window_config(&cnn);
    let max_wait = (exp.wait_s() * FRAME_RATE_HZ).ceil() as usize;
    let mut source = crate::stack::pad::open_scene(scene, &*cx.platform)?;
    let mut paced = Paced::new(&mut source, &cx.stop, Some(recorder));
    let mut trigger = TapTrigger::new(config);
    cx.progress.stage("tap-to-move: collect", n as u64);
    for (i, &region) in regions.iter().enumerate() {
        let at = format!("at tap {} of {n}", i + 1);
        ask(cx, &mut paced, region, i, n);
        trigger.restart();
        let mut waited = 0;
        let (first, last) = loop {
            if !trigger.is_triggered() {
                if waited == max_wait {
                    return Err(RunError::Ended {
                        ending: Ending::Failed,
                        what: format!("tap-to-move: no tap within {} s {at}", exp.wait_s()),
                    });
                }
                waited += 1;
            }
            let f = paced.read_frame().map_err(|e| match e {
                PadEnd::Stopped(r) => RunError::Ended {
                    ending: Ending::Stopped(r),
                    what: format!("tap-to-move: stopped by {r} {at}"),
                },
                PadEnd::Pad(e) => RunError::Ended {
                    ending: Ending::Fault,
                    what: format!("tap-to-move: {e} {at}"),
                },
            })?;
            if let Some((window, _)) = trigger.push(f) {
                break (
                    window.first().map_or(0, |f| f.t_us),
                    window.last().map_or(0, |f| f.t_us),
                );
            }
        };
        let stamp = |t_us| {
            paced.stamp_of(t_us).ok_or_else(|| RunError::Ended {
                ending: Ending::Fault,
                what: format!("tap-to-move: the window's frames were not kept {at}"),
            })
        };
        recorder.label(
            PAD_FRAME,
            &Labelled {
                experiment: EXPERIMENT,
                name: REGION,
                value: f64::from(region),
                start_ns: stamp(first)?,
                end_ns: stamp(last)?,
            },
        );
        cx.progress
            .say(&format!("  tap {} of {n}: region {region} recorded", i + 1));
        cx.progress.advance(1);
    }
    let mut part = Part::default();
    part.figures
        .push(measured("taps_collected", "taps collected", n as f64, ""));
    part.notes.push(format!(
        "{n} taps recorded into {} (the arm was not used)",
        recorder.dir().display()
    ));
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
    let f = super::figure::paper(f, PAPER_ACCURACY_PCT, PAPER_SOURCE);
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
