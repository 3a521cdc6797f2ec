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
}

impl Experiments {
    /// The names of the experiments present, in run order.
    pub fn names(&self) -> Vec<&'static str> {
        let mut v = Vec::new();
        if self.weight.is_some() {
            v.push("weight");
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
    tactile_nets::force_eval::SIM_TEST_RUN
}
fn twenty() -> Spanned<u32> {
    Spanned::new(0..0, hand_sim::fingertip::dataset::WEIGHT_STEPS)
}
fn yes() -> bool {
    true
}
