//! Seed 000 Table 1: the weight on the fingertip from its three pressures, by the force DNN.
//!
//! Two parts. The paper's own 13 rows through the committed `table1` model (trained on them:
//! the fit the paper's "Expect. Weight" column reports). And the live stack: weights of 0 →
//! 10 × `steps` gf pressed on hand-sim's pad, read by the MS5611 driver at the scene's OSR,
//! tared on the first second and estimated frame by frame by the scene's force model — the
//! committed `sim` model held out the scene's default run, so its errors here are held-out
//! errors.

use super::figure::{Target, measured, paper, target};
use super::{Part, RunContext};
use crate::scene::PaperScene;
use crate::scene::experiments::Weight;
use hand_sim::fingertip::dataset::{weight_run, weight_run_seed};
use handstack::scene::SceneOf;
use handstack::scene::force::ForceNet;
use handstack::scene::parts::ForceModel;
use handstack::{Line, Plot};
use paper_experiments::data::weights::{self, WeightSeries};
use paper_experiments::force_eval::{self, MODEL_DIR, SIM_FILE, TABLE_FILE};
use std::path::Path;
use tactile_nets::force_dnn::ForceDnn;

/// Seed 000 Table 1, cited beside every paper value.
const SOURCE: &str = "seed 000 Table 1, Expect. Weight";
/// The Table 1 fit target: every row within 0.5 gf.
const FIT_TOL_GF: f64 = 0.5;

/// Runs the weight experiment of `scene`.
pub fn run(scene: &PaperScene, exp: &Weight, cx: &RunContext<'_>) -> Result<Part, crate::Error> {
    let mut part = Part::default();
    let dir = cx.root.join(MODEL_DIR);
    if exp.table1 {
        table1(&ForceDnn::load(&dir.join(TABLE_FILE))?, &mut part)?;
    }
    series(scene, exp, &force_dnn(scene, &cx.root)?, cx, &mut part)?;
    Ok(part)
}

/// The force DNN `scene` names: its weights file, or the committed model of its built-in name
/// below the workspace root `root` (`sim` when it names none).
pub fn force_dnn<X>(scene: &SceneOf<X>, root: &Path) -> Result<ForceDnn, crate::Error> {
    let file = match &scene.force {
        Some(ForceNet::File { dnn, .. }) => return Ok(dnn.clone()),
        Some(ForceNet::BuiltIn(ForceModel::Table1)) => TABLE_FILE,
        _ => SIM_FILE,
    };
    Ok(ForceDnn::load(&root.join(MODEL_DIR).join(file))?)
}

/// The 13 rows of Table 1, tared on the 0 gf row, through `dnn`.
fn table1(dnn: &ForceDnn, part: &mut Part) -> Result<(), crate::Error> {
    let rows = paper_fixtures::seed000::table1_weight()?;
    let tared = weights::tared_table(
        &rows
            .iter()
            .map(|r| (r.weight_gf, r.pressure_hpa))
            .collect::<Vec<_>>(),
    )?;
    let (mut fit_line, mut paper_line) = (Vec::new(), Vec::new());
    let (mut worst, mut worst_paper) = (0.0f64, 0.0f64);
    for (row, s) in rows.iter().zip(&tared) {
        let fit = f64::from(dnn.estimate_gf(&s.rise_hpa)?);
        worst = worst.max((fit - row.weight_gf).abs());
        worst_paper = worst_paper.max((row.expected_weight_gf - row.weight_gf).abs());
        fit_line.push((row.weight_gf, fit));
        paper_line.push((row.weight_gf, row.expected_weight_gf));
        let key = format!("table1_fit_{}", force_eval::row_key(s.weight_gf));
        let label = format!("Table 1 fit, {} gf row", row.weight_gf);
        let f = paper(
            measured(&key, &label, fit, "gf"),
            row.expected_weight_gf,
            SOURCE,
        );
        part.figures
            .push(target(f, Target::Within(row.weight_gf, FIT_TOL_GF)));
    }
    let f = measured(
        "table1_fit_max_abs_error_gf",
        "Table 1 fit, max |error|",
        worst,
        "gf",
    );
    let f = paper(
        f,
        worst_paper,
        "seed 000 Table 1 (Expect. Weight − weight, 120 gf row)",
    );
    part.figures.push(target(f, Target::AtMost(FIT_TOL_GF)));
    part.plots.push(Plot::Lines {
        title: "Table 1: estimated vs true weight".into(),
        x_label: "weight on the pad (gf)".into(),
        y_label: "estimate (gf)".into(),
        lines: vec![
            Line {
                label: "paper's DNN".into(),
                points: paper_line,
            },
            Line {
                label: "ours (table1 model)".into(),
                points: fit_line,
            },
        ],
    });
    Ok(())
}

/// The live series on the simulated fingertip.
fn series(
    scene: &PaperScene,
    exp: &Weight,
    dnn: &ForceDnn,
    cx: &RunContext<'_>,
    part: &mut Part,
) -> Result<(), crate::Error> {
    let steps = *exp.steps.get_ref();
    let mut tip =
        crate::devices::fingertip::pressable(scene, |seed| weight_run_seed(seed, exp.run))?;
    cx.progress
        .stage("weight: fingertip series", u64::from(steps) + 1);
    let readings = weight_run(&mut tip, steps, |s| {
        if s > 0 {
            cx.progress.advance(1);
        }
    })?;
    cx.progress.advance(1);
    let frames = WeightSeries::from_readings(exp.run, &readings);
    let estimate = |samples: &[weights::WeightSample]| -> Result<Vec<(f32, f32)>, crate::Error> {
        samples
            .iter()
            .map(|s| Ok((dnn.estimate_gf(&s.rise_hpa)?, s.weight_gf)))
            .collect()
    };
    let per_frame = estimate(&frames.frame_samples(exp.run)?)?;
    let per_step = estimate(&frames.step_samples(exp.run)?)?;
    let osr = tip.osr().ratio();
    for (what, pairs) in [("frames", &per_frame), ("steps", &per_step)] {
        let e = force_eval::error_values(pairs);
        let desc = if what == "frames" {
            format!("every frame (OSR {osr})")
        } else {
            "settled-step average".to_owned()
        };
        part.figures.push(measured(
            &format!("series_{what}_n"),
            &format!("series: {desc}, samples"),
            e["n"],
            "",
        ));
        for (key, label) in [
            ("mean_abs_error_gf", "mean |error|"),
            ("rmse_gf", "RMSE"),
            ("max_abs_error_gf", "max |error|"),
        ] {
            part.figures.push(measured(
                &format!("series_{what}_{key}"),
                &format!("series: {desc}, {label}"),
                e[key],
                "gf",
            ));
        }
    }
    let t = |t_us: u64| t_us as f64 * 1e-6;
    part.plots.push(Plot::Lines {
        title: format!("Weight series at OSR {osr}: DNN estimate per frame"),
        x_label: "time (s)".into(),
        y_label: "weight (gf)".into(),
        lines: vec![
            Line {
                label: "on the pad".into(),
                points: readings.iter().map(|r| (t(r.t_us), r.weight_gf)).collect(),
            },
            Line {
                label: "estimate".into(),
                points: readings
                    .iter()
                    .zip(&per_frame)
                    .map(|(r, (e, _))| (t(r.t_us), f64::from(*e)))
                    .collect(),
            },
        ],
    });
    Ok(())
}
