//! `[experiment.*]`: what a scene runs, with its parameters. A scene names one or more
//! experiments; each runs on the stack the scene built.

use serde::Deserialize;
use toml::Spanned;

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

impl Experiments {
    /// The names of the experiments present, in run order.
    pub fn names(&self) -> Vec<&'static str> {
        let mut v = Vec::new();
        if self.weight.is_some() {
            v.push("weight");
        }
        if self.contact.is_some() {
            v.push("contact");
        }
        if self.grasp.is_some() {
            v.push("grasp");
        }
        if self.softness.is_some() {
            v.push("softness");
        }
        if self.tap.is_some() {
            v.push("tap");
        }
        if self.readout.is_some() {
            v.push("readout");
        }
        v
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

/// Which committed contact MLP of an OSR.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum MlpChoice {
    /// The validation-chosen configuration (docs/contact-location.md).
    #[default]
    Chosen,
    /// The paper's recipe, cell-set head.
    CellSet,
    /// The paper's recipe, eq. 4 average-area regression.
    AverageArea,
}

impl MlpChoice {
    /// Its file inside `fixtures/models/contact_mlp/` and its metrics row label at `osr`.
    pub fn file_and_label(self, osr: u16) -> (String, String) {
        use paper_experiments::contact_eval as ce;
        use tactile_nets::contact_mlp::Head;
        match self {
            MlpChoice::Chosen => (ce::chosen_file(osr), ce::chosen_label(osr)),
            MlpChoice::CellSet => (
                ce::model_file(osr, Head::CellSet),
                ce::row_label(osr, Head::CellSet),
            ),
            MlpChoice::AverageArea => (
                ce::model_file(osr, Head::AverageArea),
                ce::row_label(osr, Head::AverageArea),
            ),
        }
    }
}

/// Seed 000 §3–4: the held-out simulated taps (every Figure 7 shape × position × 5 / 7 / 9
/// kgf, repeat 1) at the fingertip's OSR, located by each fingertip locator the scene names.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Contact {
    /// Which committed MLP runs when the scene names `mlp` (default `chosen`).
    #[serde(default)]
    pub mlp: MlpChoice,
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

/// Seed 001 §3.3–4: the underactuated hand's grasps of the 24 regular and 30 irregular test
/// objects, classified soft / moderate / hard.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Softness {
    /// The optimiser whose selected model (lowest training MSE over the committed seeds) runs.
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
    /// Rounds of nine taps (regions 0…8), 1…3 (rows of `paper_experiments::tap_run::ROUNDS`).
    #[serde(default = "three")]
    pub rounds: Spanned<usize>,
    /// The window placement (default `aligned`).
    #[serde(default)]
    pub window: WindowPlacement,
}

fn three() -> Spanned<usize> {
    Spanned::new(0..0, 3)
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

/// Reads the fingertip at rest: frame period and per-sensor noise at its OSR.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Readout {
    /// Frames to read, 2…100 000.
    pub frames: Spanned<usize>,
}
