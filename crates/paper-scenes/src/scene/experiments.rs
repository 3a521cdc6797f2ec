//! `[experiment.*]` of a paper scene: the papers' protocols, with their parameters. A scene
//! names one or more; each runs on the stack the scene built.

use handstack::scene::experiment::{check_grasp_parts, check_hold_s, check_readout};
use handstack::scene::parts::{HandModel, Locator};
use handstack::scene::{Checker, ExperimentTable, SceneError, SceneFile};
use serde::Deserialize;
use toml::Spanned;

pub use handstack::scene::experiment::Readout;

/// The experiments of a scene (at least one).
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Experiments {
    /// `[experiment.weight]`: seed 000 Table 1 (force DNN).
    pub weight: Option<Spanned<Weight>>,
    /// `[experiment.contact]`: seed 000 §3–4 contact location on the fingertip.
    pub contact: Option<Spanned<Contact>>,
    /// `[experiment.grasp]`: seed 000 Table 5 objects held by the fuzzy loop.
    pub grasp: Option<Spanned<Grasp>>,
    /// `[experiment.softness]`: seed 001 softness classification.
    pub softness: Option<Spanned<Softness>>,
    /// `[experiment.tap]`: seed 002 §IV-B, pad taps move the UR3.
    pub tap: Option<Spanned<Tap>>,
    /// `[experiment.readout]`: read the fingertip, report its rate and noise (hardware
    /// bring-up; runs on a real or a simulated fingertip).
    pub readout: Option<Spanned<Readout>>,
}

impl ExperimentTable for Experiments {
    const ALLOWED: &'static str = "[experiment.weight], [experiment.contact], [experiment.grasp], \
                                   [experiment.softness], [experiment.tap], [experiment.readout]";

    fn names(&self) -> Vec<&'static str> {
        [
            ("weight", self.weight.is_some()),
            ("contact", self.contact.is_some()),
            ("grasp", self.grasp.is_some()),
            ("softness", self.softness.is_some()),
            ("tap", self.tap.is_some()),
            ("readout", self.readout.is_some()),
        ]
        .into_iter()
        .filter_map(|(n, on)| on.then_some(n))
        .collect()
    }

    fn check(scene: &SceneFile<Self>, cx: &Checker<'_>) -> Result<(), SceneError> {
        let s = &scene.sensors;
        let e = &scene.estimators;
        let x = scene.experiment.get_ref();
        if let Some(w) = &x.weight {
            if s.fingertip.is_none() || e.force.is_none() {
                return Err(cx.err(
                    w.span(),
                    "experiment.weight",
                    "needs the fingertip and the force DNN",
                    "[sensors.fingertip] and [estimators.force] with it",
                ));
            }
            let steps = &w.get_ref().steps;
            if !(1..=hand_sim::fingertip::dataset::WEIGHT_STEPS).contains(steps.get_ref()) {
                return Err(cx.err(
                    steps.span(),
                    "experiment.weight.steps",
                    format!("is {}", steps.get_ref()),
                    "1…20 (10 gf each, Table 1's 0–200 gf)",
                ));
            }
        }
        if let Some(c) = &x.contact {
            let fingertip_locators = e.contact.as_ref().is_some_and(|l| {
                l.get_ref()
                    .locators
                    .get_ref()
                    .iter()
                    .any(|l| *l != Locator::Cnn)
            });
            if s.fingertip.is_none() || !fingertip_locators {
                return Err(cx.err(c.span(), "experiment.contact", "needs the fingertip and a fingertip locator", "[sensors.fingertip] and [estimators.contact] locators with \"aot\", \"ranging\" or \"mlp\""));
            }
            if let Some(o) = &c.get_ref().osr {
                if !tactile_nets::pretrained::CONTACT_MLP_OSRS.contains(o.get_ref()) {
                    return Err(cx.err(
                        o.span(),
                        "experiment.contact.osr",
                        format!("is {}", o.get_ref()),
                        "256, 512, 1024, 2048 or 4096",
                    ));
                }
            }
        }
        if let Some(sx) = &x.softness {
            if s.underactuated.is_none() || e.softness.is_none() {
                return Err(cx.err(
                    sx.span(),
                    "experiment.softness",
                    "needs the underactuated hand and the softness classifier",
                    "[sensors.underactuated] and [estimators.softness] with it",
                ));
            }
        }
        if let Some(t) = &x.tap {
            let cnn = e
                .contact
                .as_ref()
                .is_some_and(|l| l.get_ref().locators.get_ref().contains(&Locator::Cnn));
            if s.imu_pad.is_none() || !cnn || scene.arm.is_none() {
                return Err(cx.err(
                    t.span(),
                    "experiment.tap",
                    "needs the ICM-20789 pad, the CNN locator and the arm",
                    "[sensors.imu_pad], [estimators.contact] locators with \"cnn\", and [arm]",
                ));
            }
            if s.imu_pad.as_ref().is_some_and(|p| p.get_ref().is_real()) {
                return Err(cx.err(
                    t.span(),
                    "experiment.tap",
                    "schedules its taps on the simulated pad",
                    "sensors.imu_pad without i2c_bus or firmata_port",
                ));
            }
            let per = &t.get_ref().taps_per_region;
            if !(1..=MAX_TAPS_PER_REGION).contains(per.get_ref()) {
                return Err(cx.err(
                    per.span(),
                    "experiment.tap.taps_per_region",
                    format!("is {}", per.get_ref()),
                    format!("1…{MAX_TAPS_PER_REGION} taps on each of the nine regions"),
                ));
            }
        }
        if let Some(g) = &x.grasp {
            check_grasp_parts(scene, g, cx)?;
            let Some(h) = &scene.hand else {
                return Ok(());
            };
            let real_tip = s.real_fingertip();
            // Real servos grasp by real sensors only: a simulated fingertip is never pressed by a
            // real grasp, so the loop would raise the torque towards the top of the band.
            if h.get_ref().serial_port.is_some() && !real_tip {
                return Err(cx.err(
                    g.span(),
                    "experiment.grasp",
                    "drives a real hand (serial_port) from a simulated fingertip",
                    "sensors.fingertip.i2c_buses or firmata_port with a hardware hand",
                ));
            }
            if h.get_ref().serial_port.is_none() {
                if h.get_ref().model != HandModel::MX28 {
                    return Err(cx.err(
                        h.span(),
                        "hand.model",
                        "is simulated, and the simulated Table 5 rig has MX-28 fingers",
                        "\"mx28\", or a serial_port for real hardware",
                    ));
                }
                let osr = s.fingertip.as_ref().map(|f| *f.get_ref().osr.get_ref());
                if osr != Some(paper_experiments::grasp_rig::OSR) {
                    return Err(cx.err(
                    g.span(),
                    "experiment.grasp",
                    "runs the simulated rig's 100 Hz loop, which reads the fingertip at OSR 1024",
                    "sensors.fingertip.osr = 1024",
                ));
                }
            }
            for o in g.get_ref().objects.get_ref() {
                if hand_sim::grasp::ObjectKind::from_name(o).is_none() {
                    return Err(cx.err(
                    g.get_ref().objects.span(),
                    "experiment.grasp.objects",
                    format!("names \"{o}\""),
                    "cube, cylinder, cone, ellipsoid, paper_cup, scroll_tissue (seed 000 Table 5)",
                ));
                }
            }
            check_hold_s(&g.get_ref().hold_s, cx)?;
        }
        if let Some(r) = &x.readout {
            check_readout(scene, r, cx)?;
        }
        for (name, needs_sim) in [
            ("weight", x.weight.is_some()),
            ("contact", x.contact.is_some()),
        ] {
            if needs_sim && s.real_fingertip() {
                return Err(cx.err(
                    scene.experiment.span(),
                    &format!("experiment.{name}"),
                    "presses the simulated pad, but the fingertip is real (i2c_buses or \
                     firmata_port)",
                    "a simulated fingertip, or [experiment.readout] on real chips",
                ));
            }
        }
        Ok(())
    }
}

/// Seed 000 Table 1's experiment: weights on the whole pad, read by the fingertip and estimated
/// by the force DNN; plus the paper's own 13 rows through the Table 1 model.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Weight {
    /// Which seeded run of the weight series to read live (the committed `sim` model was
    /// trained on runs 0 and 1 and held out run 2).
    #[serde(default = "held_out_run")]
    pub run: u32,
    /// 10 gf steps after the unloaded one (20: 0 → 200 gf, Table 1's range).
    #[serde(default = "twenty")]
    pub steps: Spanned<u32>,
    /// Also fit the paper's 13 Table 1 rows with the committed `table1` model.
    #[serde(default = "yes")]
    pub table1: bool,
}

fn held_out_run() -> u32 {
    paper_experiments::force_eval::SIM_TEST_RUN
}
fn twenty() -> Spanned<u32> {
    Spanned::new(0..0, hand_sim::fingertip::dataset::WEIGHT_STEPS)
}
fn yes() -> bool {
    true
}

/// Which committed contact MLP of an OSR (`chosen`, `off_lattice_centroid`, `off_lattice`,
/// `cell_set`, `average_area`).
pub use paper_experiments::contact_location::Mlp as MlpChoice;

/// Seed 000 §3–4: the held-out simulated taps (every Figure 7 shape × position × 5 / 7 / 9
/// kgf, repeat 1) at the fingertip's OSR, located by each fingertip locator the scene names.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Contact {
    /// Which committed MLP runs when the scene names `mlp` (default `chosen`).
    #[serde(default)]
    pub mlp: MlpChoice,
    /// The OSR the taps are read at, when not the fingertip's (one of 256, 512, 1024, 2048,
    /// 4096): an MS5611 takes its OSR with each conversion command, so one stack may read taps
    /// at one OSR and run its grasp loop at another.
    pub osr: Option<Spanned<u16>>,
}

/// The optimiser whose selected committed softness model runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Optimiser {
    /// Levenberg–Marquardt, the paper's (seed 001 §3.3).
    #[default]
    Lm,
    /// Adam (ours, for comparison).
    Adam,
}

impl Optimiser {
    /// Its name in the committed models (`lm`, `adam`).
    pub fn name(self) -> &'static str {
        match self {
            Optimiser::Lm => "lm",
            Optimiser::Adam => "adam",
        }
    }
}

/// Which committed softness models a scene runs (docs/learning.md §2).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SoftnessModel {
    /// The paper's recipe: its inputs and the protocol's 153 training grasps, LM or Adam.
    #[default]
    Paper,
    /// Our variant: finger-order-invariant inputs and more household training objects, LM.
    Ours,
}

/// Seed 001 §3.3–4: the underactuated hand's grasps of the 24 regular and 30 irregular test
/// objects, classified soft / moderate / hard.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Softness {
    /// Which committed models run: the paper's recipe (the default) or our variant.
    #[serde(default)]
    pub model: SoftnessModel,
    /// The optimiser whose selected model (lowest training MSE over the committed seeds) runs;
    /// our variant is trained with LM only.
    #[serde(default)]
    pub optimiser: Optimiser,
}

/// Where the CNN's 38-frame window sits relative to the pressure trigger.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum WindowPlacement {
    /// Where hand-sim's training windows are centred (docs/arm.md): the CNN sees what it
    /// was trained on.
    #[default]
    Aligned,
    /// 19 frames before and 19 from the trigger (§IV-A read literally).
    Trigger,
}

/// Seed 002 §IV-B: taps on the ICM-20789 pad, each located by the CNN, move the UR3 to the
/// grid pose of the touched region.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Tap {
    /// Taps on each region, 1…[`MAX_TAPS_PER_REGION`] (default
    /// `paper_experiments::tap_run::TAPS_PER_REGION`, 10): as many rounds of regions 0…8, each
    /// tap on a seeded row of its region (`paper_experiments::tap_run::schedule` with the
    /// scene seed).
    #[serde(default = "taps_per_region")]
    pub taps_per_region: Spanned<usize>,
    /// The window placement (default `aligned`).
    #[serde(default)]
    pub window: WindowPlacement,
    /// The pad's seed — its noise and the rows its taps fall on — when not the scene's (a
    /// scene with other parts keeps the tap scene's draw).
    pub seed: Option<u64>,
}

/// Most taps per region a tap scene may schedule (every tap is a move of the arm).
pub const MAX_TAPS_PER_REGION: usize = 100;

fn taps_per_region() -> Spanned<usize> {
    Spanned::new(0..0, paper_experiments::tap_run::TAPS_PER_REGION)
}

/// Seed 000 §7, Table 5: each object closed on, lifted at 3 s and held by the fuzzy grasp loop
/// inside its published torque band.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Grasp {
    /// Table 5 objects, in order (default: all six).
    #[serde(default = "table5_objects")]
    pub objects: Spanned<Vec<String>>,
    /// Hold after the lift, s (Table 5: "more than 2 min", 120).
    #[serde(default = "hold_120")]
    pub hold_s: Spanned<f64>,
    /// The fingertip's seed in each hold (docs/grasping used 7).
    #[serde(default = "seven")]
    pub seed: u64,
}

fn table5_objects() -> Spanned<Vec<String>> {
    let names = hand_sim::grasp::ObjectKind::ALL.map(|k| k.name().to_owned());
    Spanned::new(0..0, names.to_vec())
}
fn hold_120() -> Spanned<f64> {
    Spanned::new(0..0, paper_experiments::grasp_rig::HOLD_S)
}
fn seven() -> u64 {
    7
}
