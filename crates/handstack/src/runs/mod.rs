//! The experiments of a `handstack` scene, each on the real devices the scene names: a grasp
//! hold ([`grasp`]), a fingertip readout ([`readout`]), weights on the fingertip ([`weight`]),
//! taps on the fingertip located by its microcontroller ([`contact`]), the underactuated
//! hand's softness classification ([`softness`]) and taps on the pad that move the arm
//! ([`tap_to_move`]); [`run`] joins their
//! figures into
//! the scene's [`Outcome`]. The functions under them take opened devices, so a program with
//! its own devices (the papers' simulated ones) runs the same code.

pub mod contact;
pub mod figure;
pub mod grasp;
pub mod readout;
pub mod softness;
pub mod tap_to_move;
pub mod weight;

use crate::collect::Sessions;
use crate::error::RunError;
use crate::progress::Progress;
use crate::prompt::Prompter;
use crate::record::Recorder;
use crate::scene::{Scene, SceneOf};
use crate::stack::Checked;
use crate::stack::platform::{LinuxPlatform, Platform};
use crate::stop::Stop;
use crate::{Figure, Outcome, Plot};
use std::sync::{Mutex, PoisonError};
use std::time::Instant;
use ur_bridge::UrArm;

/// What every runner needs besides its scene.
pub struct RunContext<'a> {
    /// Where progress goes.
    pub progress: &'a dyn Progress,
    /// Where hardware buses, delays and the clock come from (Linux by default).
    pub platform: Box<dyn Platform>,
    /// Ends the run early (the `handstack` binary sets it on SIGINT, SIGTERM and SIGHUP).
    pub stop: Stop,
    /// Where the run is recorded, as it happens (`--record DIR`), if it is.
    pub record: Option<&'a Recorder>,
    /// Where the answers to the run's questions come from (stdin by default).
    pub prompter: Prompter,
    /// The devices the run's check left open, until an experiment takes them.
    pub checked: Mutex<Checked>,
    /// A guided collect session (`handstack collect`): the experiments ask for what the
    /// sessions before it have not recorded, and label what the user did, instead of
    /// estimating.
    pub collect: Option<Sessions>,
}

impl<'a> RunContext<'a> {
    /// Hardware through Linux's device files, reporting to `progress`.
    pub fn new(progress: &'a dyn Progress) -> Self {
        Self {
            progress,
            platform: Box::new(LinuxPlatform::new()),
            stop: Stop::new(),
            record: None,
            prompter: Prompter::stdin(),
            checked: Mutex::new(Checked::default()),
            collect: None,
        }
    }

    /// The arm at `host`: the connection the run's check made, or a new one.
    pub fn arm(&self, host: &str) -> Result<UrArm, RunError> {
        self.checked
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
            .arm(host)
    }

    /// Checks every real device `scene` names ([`check_real_devices`](crate::stack::check_real_devices)),
    /// keeping what it leaves open for the experiments; a collect session leaves the arm alone.
    pub fn check_devices<X>(&self, scene: &SceneOf<X>) -> Result<(), RunError> {
        let with_arm = self.collect.is_none();
        let checked = crate::stack::check_devices(scene, &*self.platform, with_arm)?;
        *self.checked.lock().unwrap_or_else(PoisonError::into_inner) = checked;
        Ok(())
    }

    /// Closes what the check left open and no experiment took.
    pub fn close_devices(&self) {
        drop(std::mem::take(
            &mut *self.checked.lock().unwrap_or_else(PoisonError::into_inner),
        ));
    }

    /// This context, its questions answered by `prompter` instead of stdin.
    pub fn with_prompter(self, prompter: Prompter) -> Self {
        Self { prompter, ..self }
    }

    /// This context, recording into `recorder`.
    pub fn with_record(self, recorder: &'a Recorder) -> Self {
        Self {
            record: Some(recorder),
            ..self
        }
    }

    /// This context collecting (labels recorded into `recorder`), after the sessions of
    /// `sessions`.
    pub fn with_collect(self, recorder: &'a Recorder, sessions: Sessions) -> Self {
        Self {
            record: Some(recorder),
            collect: Some(sessions),
            ..self
        }
    }

    /// This context, ended early by `stop`.
    pub fn with_stop(self, stop: Stop) -> Self {
        Self { stop, ..self }
    }

    /// This context with its hardware opened through `platform` instead of Linux's device
    /// files (another OS, a bridge, a test's substitute bus).
    pub fn with_platform(self, platform: impl Platform + 'static) -> Self {
        Self {
            platform: Box::new(platform),
            ..self
        }
    }
}

/// Figures and plots of one experiment.
#[derive(Debug, Default)]
pub struct Part {
    /// Measured figures, report order.
    pub figures: Vec<Figure>,
    /// Plot data, report order.
    pub plots: Vec<Plot>,
    /// What the run left its devices doing, one line each (`hand released …`).
    pub notes: Vec<String>,
}

impl Part {
    /// The parts joined into the outcome of `scene` (its name and title), begun at `start`.
    pub fn join<X>(scene: &SceneOf<X>, parts: Vec<Part>, start: Instant) -> Outcome {
        let (mut figures, mut plots, mut notes) = (Vec::new(), Vec::new(), Vec::new());
        for p in parts {
            figures.extend(p.figures);
            plots.extend(p.plots);
            notes.extend(p.notes);
        }
        Outcome {
            scene: scene.name.clone(),
            title: scene.file.title.clone(),
            figures,
            plots,
            notes,
            wall_s: start.elapsed().as_secs_f64(),
        }
    }
}

/// Opens every device `scene` names (failing before anything moves), then runs its
/// experiments in order and joins their figures and plots. With [`RunContext::record`], each
/// experiment's figures are recorded when it ends, and what ended the run, if something did.
pub fn run(scene: &Scene, cx: &RunContext<'_>) -> Result<Outcome, RunError> {
    let start = Instant::now();
    if let Some(r) = cx.record {
        r.note("scene", &scene.name);
    }
    let ran = run_parts(scene, cx);
    cx.close_devices();
    if let (Some(r), Err(e)) = (cx.record, &ran) {
        r.fault(&scene.name, "run", &e.to_string(), true);
    }
    Ok(Part::join(scene, ran?, start))
}

fn run_parts(scene: &Scene, cx: &RunContext<'_>) -> Result<Vec<Part>, RunError> {
    let x = scene.file.experiment.get_ref();
    cx.progress.stage("opening real devices", 0);
    cx.check_devices(scene)?;
    let mut parts = Vec::new();
    let record = |part: Part| {
        if let Some(r) = cx.record {
            r.figures(&scene.name, &part.figures);
        }
        part
    };
    if let Some(g) = &x.grasp {
        parts.push(record(grasp::run(scene, g.get_ref(), cx)?));
    }
    if let Some(r) = &x.readout {
        let mut tip = crate::stack::fingertip::open(scene, &*cx.platform)?;
        parts.push(record(readout::run(
            &mut tip,
            *r.get_ref().frames.get_ref(),
            cx.progress,
            &cx.stop,
            cx.record,
        )?));
    }
    if let Some(w) = &x.weight {
        parts.push(record(weight::run(scene, w.get_ref(), cx)?));
    }
    if let Some(c) = &x.contact {
        parts.push(record(contact::run(scene, c.get_ref(), cx)?));
    }
    if let Some(s) = &x.softness {
        parts.push(record(softness::run(scene, s.get_ref(), cx)?));
    }
    if let Some(t) = &x.tap_to_move {
        parts.push(record(tap_to_move::run(scene, t.get_ref(), cx)?));
    }
    Ok(parts)
}
