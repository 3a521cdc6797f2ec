//! Seed 000 §3–4: where the fingertip was touched. Arrival-of-Time (eq. 3 as written, and
//! aot-locate's ranging scorer) on the 3 × 3 grid, the contact MLP on the 4 × 6 grid, over the
//! held-out simulated taps (repeat 1 of `fixtures/datasets/fingertip/`, read through the
//! MS5611 driver) at the scene's OSR. The evaluation is the libraries' own
//! (`paper_experiments::aot_eval`, `paper_experiments::contact_eval`), the one the docs were written from.

use super::figure::{Target, measured, target};
use super::{Part, RunContext};
use crate::scene::PaperScene;
use crate::scene::experiments::Contact;
use aot_locate::{DetectorConfig, Geometry};
use handstack::Plot;
use handstack::scene::parts::Locator;
use paper_experiments::aot_eval::{self, Rule, Tally};
use paper_experiments::contact_eval;
use paper_experiments::data::fingertip;
use tactile_nets::contact_mlp::ContactMlp;

/// Issue 7's targets: AoT ≥ 90 % on 3 × 3, MLP ≥ 95 % on 24 areas.
const AOT_TARGET_PCT: f64 = 90.0;
const MLP_TARGET_PCT: f64 = 95.0;

/// Runs the contact experiment of `scene`.
pub fn run(scene: &PaperScene, exp: &Contact, cx: &RunContext<'_>) -> Result<Part, crate::Error> {
    let osr = scene.sim.fingertip.as_ref().map_or(4096, |f| f.osr);
    let locators = scene.locators();
    let mut part = Part::default();
    let rules: Vec<Rule> = locators
        .iter()
        .filter_map(|l| match l {
            Locator::Aot => Some(Rule::Eq3Rise),
            Locator::Ranging => Some(Rule::Ranging),
            _ => None,
        })
        .collect();
    if rules.is_empty() && !locators.contains(&Locator::Mlp) {
        return Ok(part);
    }
    let mut data = fingertip::load(&cx.root)?;
    data.retain(|t| t.osr == osr);
    if !rules.is_empty() {
        cx.progress.stage("contact: arrival-of-time", 0);
        let rep = aot_eval::evaluate(&data, &Geometry::simulated_pad(), DetectorConfig::DEFAULT);
        for rule in rules {
            aot_part(&rep, rule, osr, &mut part);
        }
    }
    if locators.contains(&Locator::Mlp) {
        cx.progress.stage("contact: MLP", 0);
        let records = data.records();
        let (_, test) = contact_eval::split(&records, osr);
        let (file, _) = exp.mlp.file_and_label(osr);
        let mlp = ContactMlp::load(&cx.root.join(contact_eval::MODEL_DIR).join(file))?;
        mlp_part(&contact_eval::evaluate(&mlp, &test)?, osr, &mut part);
    }
    Ok(part)
}

fn key(rule: Rule) -> &'static str {
    match rule {
        Rule::Eq3Rise => "aot_eq3",
        Rule::Eq3Absolute => "aot_eq3_absolute",
        Rule::Ranging => "aot_ranging",
    }
}

fn aot_part(rep: &aot_eval::Report, rule: Rule, osr: u16, part: &mut Part) {
    let k = key(rule);
    let all = rep.by_osr.get(&(rule, osr)).copied().unwrap_or_default();
    let inside = rep
        .by_interior
        .get(&(rule, osr, true))
        .copied()
        .unwrap_or_default();
    let f = measured(
        &format!("{k}_accuracy_pct"),
        &format!(
            "{}: 3 × 3 accuracy, all held-out taps (n = {})",
            rule.name(),
            all.n
        ),
        all.percent(),
        "%",
    );
    part.figures
        .push(target(f, Target::AtLeast(AOT_TARGET_PCT)));
    part.figures.push(measured(
        &format!("{k}_hits"),
        &format!("{}: hits", rule.name()),
        f64::from(all.hits),
        "",
    ));
    part.figures.push(measured(
        &format!("{k}_taps"),
        &format!("{}: held-out taps", rule.name()),
        f64::from(all.n),
        "",
    ));
    let f = measured(
        &format!("{k}_interior_accuracy_pct"),
        &format!(
            "{}: taps centred inside one area (n = {})",
            rule.name(),
            inside.n
        ),
        inside.percent(),
        "%",
    );
    part.figures
        .push(target(f, Target::AtLeast(AOT_TARGET_PCT)));
    let values = (0..9)
        .map(|a| {
            rep.by_region
                .get(&(rule, osr, a))
                .map_or(f64::NAN, Tally::percent)
        })
        .collect();
    part.plots.push(Plot::Grid {
        title: format!(
            "{} at OSR {osr}: accuracy per 3 × 3 area (Figure 11 layout)",
            rule.name()
        ),
        rows: 3,
        cols: 3,
        values,
        unit: "%".into(),
    });
}

fn mlp_part(e: &contact_eval::Evaluation, osr: u16, part: &mut Part) {
    let f = measured(
        "mlp_area_accuracy_pct",
        &format!(
            "MLP: 24-area accuracy, single-cell taps (n = {})",
            e.single_cell_taps
        ),
        100.0 * e.area_accuracy(),
        "%",
    );
    part.figures
        .push(target(f, Target::AtLeast(MLP_TARGET_PCT)));
    part.figures.push(measured(
        "mlp_exact_accuracy_pct",
        &format!("MLP: exact cell set, all taps (n = {})", e.taps),
        100.0 * e.exact_accuracy(),
        "%",
    ));
    part.figures.push(measured(
        "mlp_mean_cell_error",
        "MLP: mean |predicted ∆ touched|",
        e.mean_cell_error(),
        "cells",
    ));
    part.figures.push(measured(
        "mlp_mean_centroid_error",
        "MLP: mean centroid distance",
        e.mean_centroid_error(),
        "cells",
    ));
    part.plots.push(Plot::Grid {
        title: format!("Contact MLP at OSR {osr}: accuracy per 4 × 6 area (single-cell taps)"),
        rows: 4,
        cols: 6,
        values: e
            .per_cell
            .iter()
            .map(|&(n, hits)| {
                if n == 0 {
                    f64::NAN
                } else {
                    100.0 * f64::from(hits) / f64::from(n)
                }
            })
            .collect(),
        unit: "%".into(),
    });
}
