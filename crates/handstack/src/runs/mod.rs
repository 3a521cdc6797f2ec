//! The experiment runners: each runs one `[experiment.*]` of a scene on the stack the scene
//! names and returns its figures and plot data; [`run`] joins them into the scene's
//! [`Outcome`].

pub mod contact;
mod figure;
pub mod grasp;
pub mod hand_loop;
pub mod readout;
pub mod softness;
pub mod tap;
pub mod weight;

use crate::error::RunError;
use crate::progress::Progress;
use crate::scene::Scene;
use crate::stack::platform::{LinuxPlatform, Platform};
use crate::{Figure, Outcome, Plot};
use std::path::PathBuf;
use std::time::Instant;

/// What every runner needs besides its scene.
pub struct RunContext<'a> {
    /// The workspace root: committed models under `fixtures/models/`, datasets under
    /// `fixtures/datasets/`.
    pub root: PathBuf,
    /// Where progress goes.
    pub progress: &'a dyn Progress,
    /// Where hardware buses, delays and the clock come from (Linux by default).
    pub platform: Box<dyn Platform>,
}

impl<'a> RunContext<'a> {
    /// The workspace this crate was built in (the parent of `paper_fixtures::fixtures_dir()`,
    /// so `$HANDSTACK_FIXTURES` moves both), reporting to `progress`.
    pub fn new(progress: &'a dyn Progress) -> Self {
        let fixtures = paper_fixtures::fixtures_dir();
        Self {
            root: fixtures.parent().map_or(fixtures.clone(), PathBuf::from),
            progress,
            platform: Box::new(LinuxPlatform::new()),
        }
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
}

/// Runs every experiment `scene` names, in order, and joins their figures and plots.
pub fn run(scene: &Scene, cx: &RunContext<'_>) -> Result<Outcome, RunError> {
    let start = Instant::now();
    let x = scene.file.experiment.get_ref();
    cx.progress.stage("opening real devices", 0);
    crate::stack::check_real_devices(scene, &*cx.platform)?;
    let mut parts = Vec::new();
    if let Some(w) = &x.weight {
        parts.push(weight::run(scene, w.get_ref(), cx)?);
    }
    if let Some(c) = &x.contact {
        parts.push(contact::run(scene, c.get_ref(), cx)?);
    }
    if let Some(g) = &x.grasp {
        parts.push(grasp::run(scene, g.get_ref(), cx)?);
    }
    if let Some(s) = &x.softness {
        parts.push(softness::run(s.get_ref(), cx)?);
    }
    if let Some(t) = &x.tap {
        parts.push(tap::run(scene, t.get_ref(), cx)?);
    }
    if let Some(r) = &x.readout {
        parts.push(readout::run(scene, r.get_ref(), cx)?);
    }
    // The whole hand named: its parts again, fused into one 100 Hz control loop.
    if hand_loop::scene::applies(scene) {
        parts.push(hand_loop::scene::run(scene, cx)?);
    }
    let (mut figures, mut plots) = (Vec::new(), Vec::new());
    for p in parts {
        figures.extend(p.figures);
        plots.extend(p.plots);
    }
    Ok(Outcome {
        scene: scene.name.clone(),
        title: scene.file.title.clone(),
        figures,
        plots,
        wall_s: start.elapsed().as_secs_f64(),
    })
}
