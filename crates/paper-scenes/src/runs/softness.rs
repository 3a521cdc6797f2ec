//! Seed 001 §3.3–4: soft / moderate / hard from the underactuated hand's four FSRs and four
//! distal potentiometers. The committed 8 → 4 → 4 → 3 models run on the simulated hand's
//! grasps (`fixtures/datasets/underactuated/`, hand-sim) of the 24 regular and 30 irregular
//! test objects and of the fresh draw of 1000 irregular ones: the paper's recipe (the
//! optimiser's models) or our variant (finger-order-invariant inputs, more household training
//! objects), as the scene names; the one that runs is the selected seed (lowest training MSE,
//! chosen on training data only), through `paper_experiments::softness_eval` as
//! docs/learning.md. Irregular objects are scored against the class their fingers measure (the
//! dataset's label, with the paper's 86.66 % as target) and, with no target, against their
//! hidden overall class beside its Bayes ceiling.

use super::figure::{Target, measured, paper, target};
use super::{Part, RunContext};
use crate::scene::experiments::{Optimiser, Softness, SoftnessModel};
use hand_traits::Softness as Class;
use handstack::Plot;
use handstack::RunError;
use paper_experiments::data::underactuated::{self, GraspSet};
use paper_experiments::softness_eval::{self, Confusion};

/// Runs the softness experiment.
pub fn run(exp: &Softness, cx: &RunContext<'_>) -> Result<Part, crate::Error> {
    cx.progress.stage("softness: committed models", 0);
    let grasps = underactuated::load(&cx.root)?;
    let no_model = |name: &str| RunError::Device {
        device: "softness classifier",
        reason: format!("no committed {name} model"),
    };
    let (name, seed, e) = match exp.model {
        SoftnessModel::Paper => {
            let runs = softness_eval::load_committed(&cx.root, &grasps)?;
            let name = exp.optimiser.name();
            let run = softness_eval::selected(&runs, name).ok_or_else(|| no_model(name))?;
            (name.to_owned(), run.seed, run.evaluation)
        }
        SoftnessModel::Ours => {
            if exp.optimiser != Optimiser::Lm {
                return Err(RunError::Device {
                    device: "softness classifier",
                    reason: "our variant is trained with LM only: `optimiser = \"lm\"`".into(),
                }
                .into());
            }
            let runs = softness_eval::load_ours(&cx.root, &grasps)?;
            let run = softness_eval::selected_ours(&runs).ok_or_else(|| no_model("ours"))?;
            let name = format!("ours ({})", run.model.features.name());
            (name, run.seed, run.evaluation)
        }
    };
    let published = paper_fixtures::seed001::softness_accuracy()?;
    let mut part = Part::default();
    part.figures.push(measured(
        "softness_seed",
        &format!("{name}: selected seed (lowest training MSE)"),
        seed as f64,
        "",
    ));
    // (metrics name, the paper's row it answers, what the objects are labelled by)
    for (set, row, label, c) in [
        ("regular", "regular", "material label", &e.regular),
        (
            "irregular",
            "irregular",
            "sensor-measured label",
            &e.irregular,
        ),
        (
            "irregular_1000",
            "irregular",
            "sensor-measured label",
            &e.irregular_1000,
        ),
    ] {
        let f = measured(
            &format!("{set}_accuracy_pct"),
            &format!("{name}: {set} test objects ({} grasps, {label})", c.total()),
            100.0 * c.accuracy(),
            "%",
        );
        let f = match published.iter().find(|r| r.test_set == row) {
            Some(p) => target(
                paper(
                    f,
                    p.accuracy_pct,
                    "seed 001 §4 (fixtures/paper/seed001_softness_accuracy.csv)",
                ),
                Target::AtLeast(p.accuracy_pct),
            ),
            None => f,
        };
        part.figures.push(f);
        part.plots.push(confusion(
            &format!("Softness, {set} objects ({name}, seed {seed})"),
            c,
        ));
    }
    for (set, file_set, c) in [
        ("irregular", GraspSet::TestIrregular, &e.irregular_overall),
        (
            "irregular_1000",
            GraspSet::TestIrregular1000,
            &e.irregular_1000_overall,
        ),
    ] {
        part.figures.push(measured(
            &format!("{set}_overall_accuracy_pct"),
            &format!(
                "{name}: {set} test objects ({} grasps, hidden overall class; no target)",
                c.total()
            ),
            100.0 * c.accuracy(),
            "%",
        ));
        let ceiling = softness_eval::bayes_ceiling(&grasps, file_set)?;
        part.figures.push(measured(
            &format!("{set}_overall_bayes_ceiling_pct"),
            &format!(
                "Bayes rule on the exact local moduli, hidden overall class ({} objects)",
                ceiling.total()
            ),
            100.0 * ceiling.accuracy(),
            "%",
        ));
    }
    part.figures.push(measured(
        "train_accuracy_pct",
        &format!("{name}: training grasps"),
        100.0 * e.train.accuracy(),
        "%",
    ));
    Ok(part)
}

fn confusion(title: &str, c: &Confusion) -> Plot {
    Plot::Confusion {
        title: title.to_owned(),
        labels: Class::ALL
            .iter()
            .map(|s| softness_eval::class_name(*s).to_owned())
            .collect(),
        counts: c.counts.iter().map(|r| r.to_vec()).collect(),
    }
}
