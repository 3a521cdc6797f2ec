//! The papers' experiment runners: each runs one `[experiment.*]` of a paper scene on the
//! stack the scene names and returns its figures and plot data; [`run`] joins them into the
//! scene's [`Outcome`].

pub mod contact;
pub mod grasp;
pub mod hand_loop;
pub mod softness;
pub mod tap;
pub mod weight;

use crate::Error;
use crate::scene::PaperScene;
use handstack::Outcome;
use handstack::progress::Progress;
use handstack::runs::Part;
use std::path::PathBuf;
use std::time::Instant;

pub(crate) use handstack::runs::figure;

/// What every paper runner needs besides its scene: the stack's context (progress, the
/// platform real devices open through) and the workspace whose committed models and datasets
/// the papers' protocols read.
pub struct RunContext<'a> {
    /// The workspace root: committed models under `crates/tactile-nets/models/`, datasets under
    /// `fixtures/datasets/`.
    pub root: PathBuf,
    /// Progress and platform.
    pub stack: handstack::runs::RunContext<'a>,
}

impl<'a> RunContext<'a> {
    /// The workspace this crate was built in (the parent of `paper_fixtures::fixtures_dir()`,
    /// so `$HANDSTACK_FIXTURES` moves both), reporting to `progress`, hardware through Linux.
    pub fn new(progress: &'a dyn Progress) -> Self {
        let fixtures = paper_fixtures::fixtures_dir();
        Self {
            root: fixtures.parent().map_or(fixtures.clone(), PathBuf::from),
            stack: handstack::runs::RunContext::new(progress),
        }
    }

    /// This context with its hardware opened through `platform`.
    pub fn with_platform(
        self,
        platform: impl handstack::stack::platform::Platform + 'static,
    ) -> Self {
        Self {
            stack: self.stack.with_platform(platform),
            ..self
        }
    }
}

impl<'a> core::ops::Deref for RunContext<'a> {
    type Target = handstack::runs::RunContext<'a>;
    fn deref(&self) -> &handstack::runs::RunContext<'a> {
        &self.stack
    }
}

/// Runs every experiment `scene` names, in order, and joins their figures and plots.
pub fn run(scene: &PaperScene, cx: &RunContext<'_>) -> Result<Outcome, Error> {
    let start = Instant::now();
    let parts = run_parts(scene, cx);
    cx.close_devices();
    Ok(Part::join(&scene.scene, parts?, start))
}

fn run_parts(scene: &PaperScene, cx: &RunContext<'_>) -> Result<Vec<Part>, Error> {
    let x = scene.file.experiment.get_ref();
    cx.progress.stage("opening real devices", 0);
    cx.check_devices(&scene.scene)?;
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
        let mut tip = crate::devices::fingertip::open(scene, &*cx.platform)?;
        parts.push(handstack::runs::readout::run(
            &mut tip,
            *r.get_ref().frames.get_ref(),
            cx.progress,
            &cx.stop,
            None,
        )?);
    }
    // The whole hand named: its parts again, fused into one 100 Hz control loop.
    if hand_loop::scene::applies(scene) {
        parts.push(hand_loop::scene::run(scene, cx)?);
    }
    Ok(parts)
}
