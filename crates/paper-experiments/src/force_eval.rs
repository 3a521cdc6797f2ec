//! Evaluation of the force / weight DNN, its training recipes, and its committed weights and
//! metrics (`crates/tactile-nets/models/force_dnn/`).
//!
//! # Models
//! - `table1`: trained on seed 000 Table 1's 13 rows as printed (tared on the 0 gf row);
//!   metrics: the fit of every row, and its leave-one-out estimate (`table1-loo-WWW`: trained
//!   on the other 12 rows with the same recipe and seed), max and mean absolute errors.
//! - `sim`: trained on every frame of the hand-sim weight series' runs [`SIM_TRAIN_RUNS`],
//!   tested on run [`SIM_TEST_RUN`] (fresh sensor offsets, noise and drift): per frame, and per
//!   step on the settled-second averages (Table 1's form).
//!
//! Every model spans the rated range [`RATED_RANGE_GF`] (Table 1's 0–200 gf), fixed before
//! training so a held-out end row is an honest extrapolation.

use crate::data::weights::{WeightSample, WeightSeries};
use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use tactile_nets::error::NetError;
use tactile_nets::force_dnn::{ForceDnn, HIDDEN, series_recipe};
use tactile_nets::metrics::{MetricsFile, MetricsRow};
use tactile_nets::train::{TrainConfig, TrainLog};

/// Where the committed weights, metrics and curves live, below the workspace root.
pub const MODEL_DIR: &str = "crates/tactile-nets/models/force_dnn";
/// The committed metrics file inside [`MODEL_DIR`].
pub const METRICS_FILE: &str = "metrics.json";
/// The committed training curves inside [`MODEL_DIR`] (`model,epoch,loss`).
pub const CURVE_FILE: &str = "training_curve.csv";
/// Training seed of the committed models.
pub const SEED: u64 = 8;
/// The weights every model's output spans, gf (Table 1's range).
pub const RATED_RANGE_GF: [f32; 2] = [0.0, 200.0];
/// Simulated runs the `sim` model trains on.
pub const SIM_TRAIN_RUNS: [u32; 2] = [0, 1];
/// The held-out simulated run.
pub const SIM_TEST_RUN: u32 = 2;

/// The Table 1 recipe: full batch (13 rows), Adam 4 000 epochs at 1e-2, 4 000 at 1e-3, 2 000
/// at 1e-4.
pub fn table_recipe(seed: u64, progress: bool, label: &str) -> Vec<TrainConfig> {
    TrainConfig::stages(
        seed,
        progress,
        label,
        16,
        &[(1e-2, 4000), (1e-3, 4000), (1e-4, 2000)],
    )
}

/// The simulated-series recipe: tactile-nets' [`series_recipe`] (minibatches of 64 frames, Adam
/// 150 epochs at 3e-3, 50 at 3e-4), labelled `sim`.
pub fn sim_recipe(seed: u64, progress: bool) -> Vec<TrainConfig> {
    series_recipe(seed, progress, "sim")
}

/// File name of the leave-one-out model that held out `weight_gf`.
pub fn loo_file(weight_gf: f32) -> String {
    format!("table1-loo-{:03}.safetensors", weight_gf.round() as i64)
}

/// File name of the model trained on all of Table 1.
pub const TABLE_FILE: &str = "table1.safetensors";
/// File name of the model trained on the simulated series.
pub const SIM_FILE: &str = "sim.safetensors";

/// The trained (or loaded) models.
pub struct Models {
    /// Trained on all 13 Table 1 rows.
    pub table: ForceDnn,
    /// `loo[i]` trained on every Table 1 row but row `i`.
    pub loo: Vec<ForceDnn>,
    /// Trained on the simulated runs [`SIM_TRAIN_RUNS`].
    pub sim: ForceDnn,
    /// Training losses of `table` and `sim` (empty when loaded).
    pub logs: Vec<(String, TrainLog)>,
}

/// The simulated training and held-out frames, tared per run.
pub fn sim_split(
    frames: &WeightSeries,
) -> Result<(Vec<WeightSample>, Vec<WeightSample>), NetError> {
    let mut train = Vec::new();
    for run in SIM_TRAIN_RUNS {
        train.extend(frames.frame_samples(run)?);
    }
    Ok((train, frames.frame_samples(SIM_TEST_RUN)?))
}

/// Trains every model with the committed recipes.
pub fn train_all(
    table: &[WeightSample],
    frames: &WeightSeries,
    seed: u64,
    progress: bool,
) -> Result<Models, NetError> {
    let (full, table_log) = ForceDnn::train(
        table,
        RATED_RANGE_GF,
        &table_recipe(seed, progress, "table1"),
    )?;
    let loo = loo_models(table, seed, progress, HIDDEN)?;
    let (train, _) = sim_split(frames)?;
    let (sim, sim_log) = ForceDnn::train(&train, RATED_RANGE_GF, &sim_recipe(seed, progress))?;
    Ok(Models {
        table: full,
        loo,
        sim,
        logs: vec![("table1".into(), table_log), ("sim".into(), sim_log)],
    })
}

/// The leave-one-out models of `table` at hidden width `hidden`: model `i` trained with the
/// Table 1 recipe on every row but row `i`.
pub fn loo_models(
    table: &[WeightSample],
    seed: u64,
    progress: bool,
    hidden: usize,
) -> Result<Vec<ForceDnn>, NetError> {
    (0..table.len())
        .map(|i| {
            let rest: Vec<WeightSample> = table
                .iter()
                .enumerate()
                .filter(|&(j, _)| j != i)
                .map(|(_, s)| *s)
                .collect();
            let label = format!("loo {:>3} gf", table[i].weight_gf);
            let recipe = table_recipe(seed, progress, &label);
            Ok(ForceDnn::train_width(&rest, RATED_RANGE_GF, &recipe, hidden)?.0)
        })
        .collect()
}

/// Each leave-one-out model's `(estimate, truth)` on the row it did not see.
pub fn loo_pairs(loo: &[ForceDnn], table: &[WeightSample]) -> Result<Vec<(f32, f32)>, NetError> {
    table
        .iter()
        .zip(loo)
        .map(|(s, m)| Ok((m.estimate_gf(&s.rise_hpa)?, s.weight_gf)))
        .collect()
}

/// Loads the committed models below the workspace root `root`; `table` gives the weights of
/// the leave-one-out files.
pub fn load_committed(root: &Path, table: &[WeightSample]) -> Result<Models, NetError> {
    let dir = root.join(MODEL_DIR);
    Ok(Models {
        table: ForceDnn::load(&dir.join(TABLE_FILE))?,
        loo: table
            .iter()
            .map(|s| ForceDnn::load(&dir.join(loo_file(s.weight_gf))))
            .collect::<Result<_, _>>()?,
        sim: ForceDnn::load(&dir.join(SIM_FILE))?,
        logs: Vec::new(),
    })
}

/// Per-row key of a Table 1 weight in the metrics (`w120_gf`).
pub fn row_key(weight_gf: f32) -> String {
    format!("w{:03}_gf", weight_gf.round() as i64)
}

/// Absolute-error summary of `(estimate, truth)` pairs: `n`, `mean_abs_error_gf`,
/// `rmse_gf`, `max_abs_error_gf`.
pub fn error_values(pairs: &[(f32, f32)]) -> BTreeMap<String, f64> {
    let n = pairs.len().max(1) as f64;
    let err = |&(e, t): &(f32, f32)| f64::from(e - t).abs();
    BTreeMap::from([
        ("n".to_owned(), pairs.len() as f64),
        (
            "mean_abs_error_gf".to_owned(),
            pairs.iter().map(err).sum::<f64>() / n,
        ),
        (
            "rmse_gf".to_owned(),
            (pairs.iter().map(|p| err(p).powi(2)).sum::<f64>() / n).sqrt(),
        ),
        (
            "max_abs_error_gf".to_owned(),
            pairs.iter().map(err).fold(0.0, f64::max),
        ),
    ])
}

fn estimates(model: &ForceDnn, samples: &[WeightSample]) -> Result<Vec<(f32, f32)>, NetError> {
    samples
        .iter()
        .map(|s| Ok((model.estimate_gf(&s.rise_hpa)?, s.weight_gf)))
        .collect()
}

/// Rows `table1/fit`, `table1/loocv` (per-row estimates and error summary), `sim/frames`
/// and `sim/steps` (held-out run).
pub fn metrics_file(
    models: &Models,
    table: &[WeightSample],
    frames: &WeightSeries,
    seed: u64,
) -> Result<MetricsFile, NetError> {
    let fit = estimates(&models.table, table)?;
    let loo = loo_pairs(&models.loo, table)?;
    let table_row = |label: &str, pairs: &[(f32, f32)]| {
        let mut values = error_values(pairs);
        for &(e, t) in pairs {
            values.insert(row_key(t), f64::from(e));
        }
        MetricsRow {
            label: label.into(),
            values,
        }
    };
    let (_, test) = sim_split(frames)?;
    let steps = frames.step_samples(SIM_TEST_RUN)?;
    Ok(MetricsFile {
        model: "force_dnn".into(),
        description: "Force / weight DNN (seed 000 §2.2): Table 1 fit and leave-one-out \
                      estimates per row (gf), and held-out errors on the hand-sim weight series \
                      (per frame, and per settled-step average)."
            .into(),
        split: format!(
            "table1: all 13 rows (fit) and leave-one-out; sim: train runs {SIM_TRAIN_RUNS:?}, \
             test run {SIM_TEST_RUN}"
        ),
        seed,
        rows: vec![
            table_row("table1/fit", &fit),
            table_row("table1/loocv", &loo),
            MetricsRow {
                label: "sim/frames".into(),
                values: error_values(&estimates(&models.sim, &test)?),
            },
            MetricsRow {
                label: "sim/steps".into(),
                values: error_values(&estimates(&models.sim, &steps)?),
            },
        ],
    })
}

/// The training curves as `model,epoch,loss` CSV.
pub fn curves_csv(logs: &[(String, TrainLog)]) -> String {
    let mut s = String::from("model,epoch,loss\n");
    for (name, log) in logs {
        for (i, l) in log.epoch_loss.iter().enumerate() {
            let _ = writeln!(s, "{name},{},{l:e}", i + 1);
        }
    }
    s
}

/// Saves every model (leave-one-out files named by `table`'s weights), the metrics file and
/// the curves into `dir`; returns the files written.
pub fn save_all(
    dir: &Path,
    models: &Models,
    table: &[WeightSample],
    metrics: &MetricsFile,
) -> Result<Vec<PathBuf>, NetError> {
    std::fs::create_dir_all(dir)?;
    let mut written = vec![dir.join(TABLE_FILE), dir.join(SIM_FILE)];
    models.table.save(&written[0])?;
    models.sim.save(&written[1])?;
    for (model, row) in models.loo.iter().zip(table) {
        let path = dir.join(loo_file(row.weight_gf));
        model.save(&path)?;
        written.push(path);
    }
    for (name, text) in [
        (METRICS_FILE, metrics.to_json()?),
        (CURVE_FILE, curves_csv(&models.logs)),
    ] {
        std::fs::write(dir.join(name), text)?;
        written.push(dir.join(name));
    }
    Ok(written)
}
