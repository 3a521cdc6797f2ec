//! `papers docs softness`: from the softness classifier's committed files (seed 001, LM and
//! Adam, one model per seed: `crates/tactile-nets/models/softness/`, written by `papers train softness`,
//! i.e. `paper_experiments::jobs::softness`), draws the confusion matrices and training curves
//! into `docs/learning/` and rewrites section 2 of `docs/learning.md` (only that section) from
//! `metrics.json` and `training.json`.

use super::plot::{draw_legend, legend_mark, plot_err};
use anyhow::{Context, Result};
use paper_experiments::softness_eval::{
    METRICS_FILE, MODEL_DIR, OURS_METRICS_FILE, SEEDS, STRIDE, TRAIN_DRAW, TRAINING_FILE,
    VALIDATION_DRAW, VALIDATION_FILE, row_label,
};
use paper_fixtures::seed001::{SoftnessAccuracyRow, softness_accuracy_in};
use plotters::prelude::*;
use serde_json::Value;
use std::fmt::Write as _;
use std::path::Path;
use tactile_nets::metrics::MetricsFile;

/// The report this command writes one section of.
pub(crate) const DOC: &str = "docs/learning.md";
/// The heading of that section (the text up to the next `## ` is replaced).
pub(crate) const HEADING: &str = "## 2. Softness classifier, Levenberg–Marquardt (seed 001 §3.3–4)";
/// Confusion matrices of the selected LM and Adam models.
pub(crate) const CONFUSION_SVG: &str = "docs/learning/softness-confusion.svg";
/// Training curves of every run.
pub(crate) const CURVES_SVG: &str = "docs/learning/softness-training.svg";

const CLASSES: [&str; 3] = ["soft", "moderate", "hard"];
/// The test sets: metrics key, name, objects, and the paper's row (§4) whose figure it is
/// compared with.
const SETS: [(&str, &str, u32, &str); 3] = [
    (
        "regular",
        "24 regular shapes (material label)",
        24,
        "regular",
    ),
    (
        "irregular",
        "30 irregular objects (sensor-measured label)",
        30,
        "irregular",
    ),
    (
        "irregular_1000",
        "1000 fresh irregular objects (sensor-measured label)",
        1000,
        "irregular",
    ),
];

/// The paper's figure (§4) for the paper row `row`.
fn paper_pct(paper: &[SoftnessAccuracyRow], row: &str) -> f64 {
    paper
        .iter()
        .find(|r| r.test_set == row)
        .map_or(f64::NAN, |r| r.accuracy_pct)
}

/// Draws the figures and writes the section from the committed files.
pub(crate) fn write(root: &Path) -> Result<()> {
    let paper = softness_accuracy_in(&root.join("fixtures"))?;
    let dir = root.join(MODEL_DIR);
    let metrics = MetricsFile::from_json(&std::fs::read_to_string(dir.join(METRICS_FILE))?)?;
    let training: Vec<Value> = serde_json::from_str(
        &std::fs::read_to_string(dir.join(TRAINING_FILE)).context("reading training.json")?,
    )?;
    std::fs::create_dir_all(root.join("docs/learning"))?;
    confusion_plot(&metrics, &root.join(CONFUSION_SVG))?;
    curves_plot(&training, &root.join(CURVES_SVG))?;
    let ours = MetricsFile::from_json(&std::fs::read_to_string(dir.join(OURS_METRICS_FILE))?)?;
    let validation: Value = serde_json::from_str(
        &std::fs::read_to_string(dir.join(VALIDATION_FILE)).context("reading validation.json")?,
    )?;
    let mut section = section(root, &metrics, &training, &paper)?;
    section += &ours_section(&ours, &validation, &paper)?;
    section += &differ(root, &metrics, &ours, &validation, &paper)?;
    super::section::write(&root.join(DOC), HEADING, &section)?;
    println!("wrote {CONFUSION_SVG}, {CURVES_SVG} and {DOC} § 2\n\n{section}");
    Ok(())
}

fn value(m: &MetricsFile, label: &str, key: &str) -> f64 {
    m.row(label)
        .and_then(|r| r.values.get(key).copied())
        .unwrap_or(f64::NAN)
}

fn selected_seed(m: &MetricsFile, opt: &str) -> u64 {
    value(m, "selected", &format!("{opt}_seed")) as u64
}

fn confusion_table(s: &mut String, c: &[[u32; 3]; 3]) -> Result<()> {
    writeln!(
        s,
        "| true \\ predicted | soft | moderate | hard |\n|---|---:|---:|---:|"
    )?;
    for (t, row) in c.iter().enumerate() {
        writeln!(
            s,
            "| {} | {} | {} | {} |",
            CLASSES[t], row[0], row[1], row[2]
        )?;
    }
    Ok(())
}

/// Our variant's subsection: validation choice, accuracies and confusion matrices.
fn ours_section(
    m: &MetricsFile,
    validation: &Value,
    paper: &[SoftnessAccuracyRow],
) -> Result<String> {
    let mut s = String::new();
    let chosen = validation["chosen"].as_str().unwrap_or("?");
    let seed = value(m, "ours/selected", "lm_seed") as u64;
    let label = |seed: u64| format!("ours/{chosen}/lm/seed{seed}");
    let acc = |name: &str| 100.0 * validation["accuracy"][name].as_f64().unwrap_or(f64::NAN);
    let objects = |key: &str| validation[key].as_u64().unwrap_or(0);
    writeln!(
        s,
        "### Our variant: finger-order-invariant inputs, more household training objects (`{OURS_METRICS_FILE}`)\n\n\
         The same 8 → 4 → 4 → 3 network and LM recipe, with two changes, both decided on \
         training-side data only:\n\n\
         - **Inputs** that do not depend on which finger met which side of the object \
         (`tactile_nets::softness_features`): *sorted_series* sorts the four forces and the four \
         angles of every sample; *finger_stiffness* is one row per grasp, each finger's force \
         gained over distal-angle travel (`ln((Δf + 0.05 N) / (Δa⁺ + 0.5°))`, from 0.5 N to 2 N \
         and to 15 N), the four of each level sorted.\n\
         - **Training objects:** the 153 protocol grasps and {} household objects drawn at \
         training time from the same generator and law (`hand_sim::underactuated::dataset::\
         household_draw`, the dataset's seed, stream `{TRAIN_DRAW}`), labelled by the same \
         sensor-measured rule — the paper's 18 household objects leave the label's boundaries \
         almost without data (below).\n\
         - **Choice:** the inputs by their accuracy on {} household validation objects of their \
         own draw (stream `{VALIDATION_DRAW}`, never trained on), LM seed {}; the seed by \
         lowest training MSE on the 153 protocol grasps. The test sets are not read until the \
         choice is made.\n",
        objects("training_objects"),
        objects("validation_objects"),
        validation["seed"].as_u64().unwrap_or(0),
    )?;
    writeln!(
        s,
        "| inputs | validation accuracy ({} household validation objects) |\n|---|---:|",
        objects("validation_objects")
    )?;
    for name in ["paper", "sorted_series", "finger_stiffness"] {
        let mark = if name == chosen { " (chosen)" } else { "" };
        writeln!(s, "| {name}{mark} | {:.1} % |", acc(name))?;
    }
    writeln!(
        s,
        "\n| test set | paper (§4) | ours `{chosen}`, selected (seed {seed}) | ours, seeds {}–{}: mean (min–max) |\n|---|---:|---:|---:|",
        SEEDS[0],
        SEEDS[SEEDS.len() - 1]
    )?;
    for &(set, name, n, row) in &SETS {
        let p = paper_pct(paper, row);
        let key = format!("{set}_accuracy");
        // Our labels are `ours/<features>/lm/seed<N>`: `spread` over that prefix.
        let (mean, lo, hi) = spread(m, &format!("ours/{chosen}/lm"), &key);
        let sel = 100.0 * value(m, &label(seed), &key);
        writeln!(
            s,
            "| {name} | {p:.2} % | **{sel:.2} %** ({}/{n}) | {mean:.1} % ({lo:.1}–{hi:.1}) |",
            (sel * f64::from(n) / 100.0).round()
        )?;
    }
    writeln!(s)?;
    for (set, name, _, _) in SETS {
        writeln!(s, "Ours, {name}:\n")?;
        confusion_table(&mut s, &counts(m, &label(seed), set))?;
        writeln!(s)?;
    }
    Ok(s)
}

fn counts(m: &MetricsFile, label: &str, set: &str) -> [[u32; 3]; 3] {
    core::array::from_fn(|t| {
        core::array::from_fn(|p| {
            value(m, label, &format!("{set}_cm_{}_{}", CLASSES[t], CLASSES[p])) as u32
        })
    })
}

/// (mean, min, max) of `key` over the seeds of `opt`, in percent.
fn spread(m: &MetricsFile, opt: &str, key: &str) -> (f64, f64, f64) {
    let v: Vec<f64> = SEEDS
        .iter()
        .map(|&s| 100.0 * value(m, &row_label(opt, s), key))
        .collect();
    let mean = v.iter().sum::<f64>() / v.len() as f64;
    (
        mean,
        v.iter().copied().fold(f64::INFINITY, f64::min),
        v.iter().copied().fold(f64::NEG_INFINITY, f64::max),
    )
}

fn runs<'a>(training: &'a [Value], opt: &'a str) -> impl Iterator<Item = &'a Value> + 'a {
    training.iter().filter(move |r| r["optimiser"] == opt)
}

fn median_seconds(training: &[Value], opt: &str) -> f64 {
    let mut s: Vec<f64> = runs(training, opt)
        .filter_map(|r| r["seconds"].as_f64())
        .collect();
    s.sort_by(f64::total_cmp);
    s.get(s.len() / 2).copied().unwrap_or(f64::NAN)
}

fn section(
    root: &Path,
    m: &MetricsFile,
    training: &[Value],
    paper: &[SoftnessAccuracyRow],
) -> Result<String> {
    let mut s = String::new();
    let (lm, adam) = (selected_seed(m, "lm"), selected_seed(m, "adam"));
    let lm_label = row_label("lm", lm);
    writeln!(
        s,
        "Generated by `cargo xtask train softness` (weights, `metrics.json`, `training.json` in \
         `{MODEL_DIR}/`; `crates/paper-experiments/tests/it/nets_softness.rs` re-evaluates the committed \
         weights against `metrics.json`).\n\n\
         **Network** (seed 001 §3.3): 8 inputs → 4 logistic-sigmoid → 4 logistic-sigmoid → 3 \
         linear outputs (71 parameters), in nalgebra (`tactile_nets::softness`), least squares \
         on one-hot targets (soft, moderate, hard).\n\n\
         **Feature vector** (§3.1): one input is one sample of the grasp's series, \
         `[f1, f2, f3, f4 (FSR force, N), a1, a2, a3, a4 (distal joint angle, deg)]`, fingers 1–4, \
         each mapped to [−1, 1] by the training minimum / maximum (Matlab's `mapminmax`). \
         Training rows: every {STRIDE}th sample of each series (1.4 s apart, 11 per grasp, \
         1683 rows). A grasp is classified by the mean of the network's outputs over all 141 \
         samples of its series (t₁ … t₁ + 14 s, 10 Hz); the largest mean wins.\n\n\
         **Labels** (fixed before any net was trained on them): model and regular \
         objects carry their material's class; every household object (training and test) the \
         class its fingers measure — the class band holding the median of its four local moduli \
         (`hand_sim::underactuated::dataset::sensor_class`; the rule in \
         `docs/sim-calibration/underactuated.md` and the dataset's README). The hidden overall \
         class stays in the dataset and is scored below beside its Bayes ceiling, with no \
         target.\n\n\
         **Protocol** (§3.3–4): train on the 153 labelled grasps of the simulated dataset \
         (27 model objects × 5 poses + 18 household objects; the 6 empty grasps have no class \
         among the three and are left out); test on the 24 regular-shape and the 30 irregular \
         objects of the paper's protocol, and on a fresh seeded draw of 1000 household objects \
         from the same generator (`test_irregular_1000`: at 30 objects one object is 3.3 \
         points, at 1000 the standard error of an 80 % figure is 1.3 points). Seeds \
         {SEEDS:?}; the *selected* model of an optimiser is its seed of lowest training MSE \
         (chosen on training data only): LM seed {lm}, Adam seed {adam}.\n\n\
         **Training**: Levenberg–Marquardt by the `levenberg-marquardt` crate with the analytic \
         Jacobian (`LeastSquaresProblem`), tolerances 1e-10, patience 3 (at most 216 residual \
         evaluations: Matlab `trainlm`'s role, capped to keep the run short); Adam: the same \
         network and derivative (gradient `Jᵀr / m`), full batch, 2000 epochs at 0.01. Initial \
         weights Glorot-uniform from the seed.\n"
    )?;
    writeln!(s, "### Against the paper\n")?;
    writeln!(
        s,
        "| test set | paper (§4) | LM, selected (seed {lm}) | LM, seeds {}–{}: mean (min–max) | Adam, selected (seed {adam}) | Adam, seeds: mean (min–max) |",
        SEEDS[0],
        SEEDS[SEEDS.len() - 1]
    )?;
    writeln!(s, "|---|---:|---:|---:|---:|---:|")?;
    for &(set, name, n, row) in &SETS {
        let paper = paper_pct(paper, row);
        let key = format!("{set}_accuracy");
        let (lm_m, lm_lo, lm_hi) = spread(m, "lm", &key);
        let (ad_m, ad_lo, ad_hi) = spread(m, "adam", &key);
        let acc = |opt: &str, seed: u64| 100.0 * value(m, &row_label(opt, seed), &key);
        writeln!(
            s,
            "| {name} | {paper:.2} % | **{:.2} %** ({}/{n}) | {lm_m:.1} % ({lm_lo:.1}–{lm_hi:.1}) | {:.2} % | {ad_m:.1} % ({ad_lo:.1}–{ad_hi:.1}) |",
            acc("lm", lm),
            (acc("lm", lm) * f64::from(n) / 100.0).round(),
            acc("adam", adam),
        )?;
    }
    let (tr_m, tr_lo, tr_hi) = spread(m, "lm", "train_accuracy");
    writeln!(
        s,
        "\nTraining-set accuracy (LM, all seeds): {tr_m:.1} % ({tr_lo:.1}–{tr_hi:.1}).\n"
    )?;
    writeln!(
        s,
        "### The hidden overall class (no target)\n\n\
         The same nets scored against the household objects' hidden overall class, beside the \
         Bayes rule that knows each object's four local moduli exactly and the generator's law \
         (`hand_sim::underactuated::ceiling`, `fixtures/datasets/underactuated/ceiling.csv`), \
         and beside the sensor-measured label itself read as a guess of the hidden class \
         (`labels.csv`):\n\n\
         | test set | LM, selected (seed {lm}) | LM, seeds: mean (min–max) | Bayes ceiling | label = hidden class |\n\
         |---|---:|---:|---:|---:|"
    )?;
    for (set, file_set, n) in [
        ("irregular_overall", "test_irregular", 30u32),
        ("irregular_1000_overall", "test_irregular_1000", 1000),
    ] {
        let key = format!("{set}_accuracy");
        let (mean, lo, hi) = spread(m, "lm", &key);
        let sel = 100.0 * value(m, &lm_label, &key);
        let [_, bayes_k, bayes] = ceiling_row(root, file_set)?;
        let agree = dataset_row(root, "labels.csv", file_set)?;
        writeln!(
            s,
            "| {n} irregular objects | {sel:.2} % ({}/{n}) | {mean:.1} % ({lo:.1}–{hi:.1}) | {:.1} % ({bayes_k}/{n}) | {:.1} % ({}/{n}) |",
            (sel * f64::from(n) / 100.0).round(),
            100.0 * bayes,
            100.0 * agree.get(2).copied().unwrap_or(f64::NAN),
            agree.get(1).copied().unwrap_or(f64::NAN),
        )?;
    }
    writeln!(s)?;
    writeln!(s, "### LM against Adam (same network, same derivative)\n")?;
    writeln!(
        s,
        "| optimiser | stop | residual evaluations / epochs | training MSE, selected | training wall time (median of 5 seeds, this run) |"
    )?;
    writeln!(s, "|---|---|---:|---:|---:|")?;
    for (opt, seed) in [("lm", lm), ("adam", adam)] {
        let run = runs(training, opt).find(|r| r["seed"] == seed);
        let stop = run.and_then(|r| r["stop"].as_str()).unwrap_or("?");
        let evals = run.and_then(|r| r["evaluations"].as_u64()).unwrap_or(0);
        writeln!(
            s,
            "| {} | {stop} | {evals} | {:.4} | {:.2} s |",
            if opt == "lm" {
                "Levenberg–Marquardt"
            } else {
                "Adam"
            },
            value(m, &row_label(opt, seed), "train_mse"),
            median_seconds(training, opt),
        )?;
    }
    writeln!(
        s,
        "\nWall times come from the training run on a shared 2-core machine (other builds \
         running): compare them with each other, not with another machine. The criterion bench \
         `cargo xtask bench softness` measures single-sample inference and both training runs.\n"
    )?;
    writeln!(
        s,
        "### Confusion matrices (selected LM model, rows = true class, columns = predicted)\n"
    )?;
    for (set, name, _, _) in SETS {
        writeln!(s, "{name}:\n")?;
        confusion_table(&mut s, &counts(m, &lm_label, set))?;
        writeln!(s)?;
    }
    writeln!(
        s,
        "![Confusion matrices of the selected LM and Adam models](learning/softness-confusion.svg)\n"
    )?;
    writeln!(
        s,
        "![Training MSE of every run: LM per residual evaluation (best so far), Adam per epoch](learning/softness-training.svg)\n"
    )?;
    Ok(s)
}

fn confusion_plot(m: &MetricsFile, path: &Path) -> Result<()> {
    let root = SVGBackend::new(path, (450 * SETS.len() as u32, 760)).into_drawing_area();
    root.fill(&WHITE).map_err(plot_err)?;
    let panels = root.split_evenly((2, SETS.len()));
    let mut i = 0;
    for opt in ["lm", "adam"] {
        let seed = selected_seed(m, opt);
        for (set, name, _, _) in SETS {
            let c = counts(m, &row_label(opt, seed), set);
            let total: u32 = c.iter().flatten().sum();
            let correct: u32 = (0..3).map(|k| c[k][k]).sum();
            let title = format!(
                "{} seed {seed}: {} objects ({:.1} %)",
                if opt == "lm" { "LM" } else { "Adam" },
                name.split(' ').next().unwrap_or(name),
                100.0 * f64::from(correct) / f64::from(total.max(1))
            );
            let mut chart = ChartBuilder::on(&panels[i])
                .caption(title, ("sans-serif", 17))
                .margin(12)
                .x_label_area_size(40)
                .y_label_area_size(70)
                .build_cartesian_2d(0.0..3.0, 0.0..3.0)
                .map_err(plot_err)?;
            let label = |v: &f64| {
                let k = (v - 0.5).round();
                if (v - 0.5 - k).abs() < 1e-6 && (0.0..3.0).contains(&k) {
                    CLASSES[k as usize].to_owned()
                } else {
                    String::new()
                }
            };
            chart
                .configure_mesh()
                .disable_mesh()
                .x_desc("predicted")
                .y_desc("true")
                .x_labels(7)
                .y_labels(7)
                .x_label_formatter(&label)
                .y_label_formatter(&|v| label(&(3.0 - v)))
                .draw()
                .map_err(plot_err)?;
            let max = c.iter().flatten().copied().max().unwrap_or(1).max(1);
            for (t, row) in c.iter().enumerate() {
                for (p, &n) in row.iter().enumerate() {
                    // True class from the top, as the paper's Figures 11–12 read.
                    let (x, y) = (p as f64, 2.0 - t as f64);
                    let shade = 1.0 - 0.75 * f64::from(n) / f64::from(max);
                    let base = if t == p {
                        (40.0, 110.0, 200.0)
                    } else {
                        (210.0, 60.0, 50.0)
                    };
                    let mix = |b: f64| (255.0 * shade + b * (1.0 - shade)) as u8;
                    let fill = RGBColor(mix(base.0), mix(base.1), mix(base.2));
                    chart
                        .draw_series([Rectangle::new([(x, y), (x + 1.0, y + 1.0)], fill.filled())])
                        .map_err(plot_err)?;
                    chart
                        .draw_series([Text::new(
                            n.to_string(),
                            (x + 0.45, y + 0.6),
                            ("sans-serif", 22),
                        )])
                        .map_err(plot_err)?;
                }
            }
            i += 1;
        }
    }
    root.present().map_err(plot_err)?;
    Ok(())
}

fn curves_plot(training: &[Value], path: &Path) -> Result<()> {
    let root = SVGBackend::new(path, (960, 400)).into_drawing_area();
    root.fill(&WHITE).map_err(plot_err)?;
    let (left, right) = root.split_horizontally(480);
    let colors = [RED, BLUE, GREEN, MAGENTA, CYAN];
    for (area, opt, xdesc, name) in [
        (
            &left,
            "lm",
            "residual evaluation",
            "Levenberg–Marquardt (best so far)",
        ),
        (&right, "adam", "epoch", "Adam (full batch)"),
    ] {
        let curves: Vec<(u64, Vec<f64>)> = runs(training, opt)
            .map(|r| {
                let c: Vec<f64> = r["curve"]
                    .as_array()
                    .map(|a| a.iter().filter_map(Value::as_f64).collect())
                    .unwrap_or_default();
                // LM also evaluates rejected trial steps: plot the best accepted so far.
                let c = if opt == "lm" {
                    c.iter()
                        .scan(f64::INFINITY, |b, &v| {
                            *b = b.min(v);
                            Some(*b)
                        })
                        .collect()
                } else {
                    c
                };
                (r["seed"].as_u64().unwrap_or(0), c)
            })
            .collect();
        let n = curves
            .iter()
            .map(|(_, c)| c.len())
            .max()
            .unwrap_or(1)
            .max(2) as f64;
        let hi = curves
            .iter()
            .flat_map(|(_, c)| c.iter().copied())
            .fold(0.0f64, f64::max)
            .clamp(0.1, 10.0);
        let mut chart = ChartBuilder::on(area)
            .caption(name, ("sans-serif", 18))
            .margin(10)
            .x_label_area_size(35)
            .y_label_area_size(55)
            .build_cartesian_2d(0.0..n, (0.02f64..hi * 1.1).log_scale())
            .map_err(plot_err)?;
        chart
            .configure_mesh()
            .x_desc(xdesc)
            .y_desc("training MSE")
            .draw()
            .map_err(plot_err)?;
        for ((seed, c), color) in curves.iter().zip(colors) {
            chart
                .draw_series(LineSeries::new(
                    c.iter().enumerate().map(|(i, &v)| (i as f64, v.max(0.02))),
                    color.stroke_width(2),
                ))
                .map_err(plot_err)?
                .label(format!("seed {seed}"))
                .legend(legend_mark(color));
        }
        draw_legend(&mut chart, SeriesLabelPosition::MiddleRight)?;
    }
    root.present().map_err(plot_err)?;
    Ok(())
}

/// The numbers after `set` in the row of `set` of the dataset's `file` (`#` lines skipped).
fn dataset_row(root: &Path, file: &str, set: &str) -> Result<Vec<f64>> {
    let path = root.join("fixtures/datasets/underactuated").join(file);
    let text = std::fs::read_to_string(&path).with_context(|| format!("reading {file}"))?;
    let row = text
        .lines()
        .filter(|l| !l.starts_with('#'))
        .map(|l| l.split(',').collect::<Vec<_>>())
        .find(|f| f[0] == set)
        .with_context(|| format!("{file} has no row `{set}`"))?;
    row[1..]
        .iter()
        .map(|v| v.parse::<f64>().with_context(|| format!("{file}: `{v}`")))
        .collect()
}

/// A row of `ceiling.csv`: objects, correct, accuracy.
fn ceiling_row(root: &Path, set: &str) -> Result<[f64; 3]> {
    dataset_row(root, "ceiling.csv", set)?
        .try_into()
        .map_err(|_| anyhow::anyhow!("ceiling.csv: `{set}` needs objects, correct, accuracy"))
}

/// Where the figures differ from the paper's, and why.
fn differ(
    root: &Path,
    m: &MetricsFile,
    ours: &MetricsFile,
    validation: &Value,
    paper: &[SoftnessAccuracyRow],
) -> Result<String> {
    let floor =
        |set: &str| -> Result<f64> { Ok(100.0 * dataset_row(root, "separability.csv", set)?[1]) };
    let target = paper_pct(paper, "irregular");
    let regular_target = paper_pct(paper, "regular");
    let lm = selected_seed(m, "lm");
    let pct = |f: &MetricsFile, label: &str, key: &str| 100.0 * value(f, label, key);
    let lm_label = row_label("lm", lm);
    let (regular, irregular, large) = (
        pct(m, &lm_label, "regular_accuracy"),
        pct(m, &lm_label, "irregular_accuracy"),
        pct(m, &lm_label, "irregular_1000_accuracy"),
    );
    // The best 1000-set figure of every committed model (15: LM, Adam and the variant, 5 seeds
    // each): whether any of them meets the target, i.e. whether selection could have.
    let mut best = (f64::NEG_INFINITY, String::new());
    for f in [m, ours] {
        for row in &f.rows {
            if let Some(v) = row.values.get("irregular_1000_accuracy")
                && 100.0 * v > best.0
            {
                best = (100.0 * v, row.label.clone());
            }
        }
    }
    let acc = |name: &str| 100.0 * validation["accuracy"][name].as_f64().unwrap_or(f64::NAN);
    let chosen = validation["chosen"].as_str().unwrap_or("?");
    let seed = value(ours, "ours/selected", "lm_seed") as u64;
    let ours_label = format!("ours/{chosen}/lm/seed{seed}");
    let (o_regular, o_irregular, o_large) = (
        pct(ours, &ours_label, "regular_accuracy"),
        pct(ours, &ours_label, "irregular_accuracy"),
        pct(ours, &ours_label, "irregular_1000_accuracy"),
    );
    let extra = validation["training_objects"].as_u64().unwrap_or(0);
    let held = validation["validation_objects"].as_u64().unwrap_or(0);
    let met = |v: f64, t: f64| if v >= t { "met" } else { "not met" };
    let (paper_in, sorted_in, stiffness_in) =
        (acc("paper"), acc("sorted_series"), acc("finger_stiffness"));
    let (floor_30, floor_1000) = (floor("test_irregular")?, floor("test_irregular_1000")?);
    let agree = 100.0 * dataset_row(root, "labels.csv", "test_irregular_1000")?[2];
    let bayes = 100.0 * ceiling_row(root, "test_irregular_1000")?[2];
    let (best_label, best_pct) = (&best.1, best.0);
    let mut s = String::new();
    writeln!(
        s,
        "### Where we differ from the paper, and why\n\n\
         - **Regular shapes: target {} by the paper's recipe, {} by our variant.** The \
         selected LM net gets {regular:.2} % and our variant {o_regular:.2} % against the \
         paper's {regular_target:.2} % (the paper's: 1 of 24 wrong).\n\
         - **Irregular objects, sensor-measured label: target {} on the 30 and {} on the 1000 \
         by our variant; {} and {} by the paper's recipe.** Our variant (`{chosen}` inputs, \
         {extra} more household training objects, selected seed {seed} by training MSE) gets \
         {o_irregular:.2} % of the 30 and {o_large:.1} % of the 1000 against the paper's \
         {target:.2} %; the scene runs it (`fixtures/scenes/softness.toml`, `model = \"ours\"`). \
         The paper's recipe (selected LM net, seed {lm}) gets {irregular:.2} % and \
         {large:.1} %. Our variant's inputs by validation on the {held} household validation objects: \
         paper inputs {paper_in:.1} %, sorted series {sorted_in:.1} %, per-finger stiffness \
         {stiffness_in:.1} %. Best 1000-set figure of the 15 committed models: `{best_label}` \
         at {best_pct:.1} %. The nearest-centroid floor on the end-of-series readings \
         (`separability.csv`) is {floor_30:.1} % on the 30 and {floor_1000:.1} % on the 1000. \
         Tried before the extra objects (commit `c682456`): the same variant on the 153 \
         protocol grasps alone, inputs chosen on 3 folds of the 18 household training objects, \
         83.33 % of the 30 and 81.2 % of the 1000.\n\
         - **Why the paper's protocol is not enough here.** The label is exact in the local \
         moduli, but the series show each modulus only through force and distal angle, which \
         also move with shape, size (55–110 mm), local width (±15 %) and pose. And the label's \
         boundaries (51.96 kPa, 3.162 MPa) lie where the protocol's training data are thin: 135 \
         of its 153 training grasps are model objects at 25 kPa, 0.12 MPa and 10 GPa, far from \
         both boundaries (in ln, the soft | moderate boundary is near their midpoint; the \
         moderate | hard one is not: the midpoint of 0.12 MPa and 10 GPa is 35 MPa, ten times \
         the label's 3.16 MPa), and only its 18 household objects (1 object = 5.6 validation \
         points) say where the boundaries are. Our variant adds household objects from the \
         same generator (streams `{TRAIN_DRAW}` and `{VALIDATION_DRAW}`, which no committed set \
         uses); the paper's recipe keeps the protocol's 153 grasps; the simulator's law was not \
         changed. How many to add was decided on an exploratory draw of another seed, before \
         any of these models was trained: with the 153 grasps and 0 / 125 / 250 / 500 of its \
         household objects the variant scored 76–80 / 86–88 / 85–87 / 89 % of 500 others of \
         that draw; {extra}, as many as the large test draw, was then fixed. Test exposure, \
         stated: the training runs print every model's test figures, so earlier candidates' \
         test figures were seen; no choice above reads a test set.\n\
         - **Hidden overall class.** Reported above beside its Bayes ceiling, no target. The \
         sensor-measured label itself agrees with the hidden class on {agree:.1} % of the 1000 \
         (`labels.csv`), below the Bayes rule's {bayes:.1} %: the two questions differ.\n\
         - **Series and stop.** The paper trains on the series in Matlab's `trainlm` with its \
         defaults (not stated); we cap LM at 216 evaluations and subsample the series for \
         training (every {STRIDE}th sample) to keep the run to seconds; the Jacobian is \
         1683 × 3 rows by 71 columns.\n",
        met(regular, regular_target),
        met(o_regular, regular_target),
        met(o_irregular, target),
        met(o_large, target),
        met(irregular, target),
        met(large, target),
    )?;
    Ok(s)
}
