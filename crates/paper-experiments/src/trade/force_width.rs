//! Model-size knob of the force / weight DNN (seed 000 §2.2, Table 1): hidden width against
//! leave-one-out error on Table 1 and CPU per estimate. Every width is trained here with the
//! committed recipe and seed (`force_eval::table_recipe`, 10 000 full-batch epochs per model).

use super::error::TradeError;
use super::pareto::Better;
use super::point::{CostKind, Point, Task};
use super::timing::median_us;
use crate::data::weights::{self, WeightSample};
use crate::force_eval::{self, error_values, loo_models, loo_pairs};
use std::path::Path;
use tactile_nets::force_dnn::{HIDDEN, WIDTHS};

/// Task id.
pub const TASK: &str = "force-dnn-width";

/// The task.
pub fn task() -> Task {
    Task {
        id: TASK,
        title: "Force / weight DNN: hidden width",
        cost: CostKind::Cpu,
        cost_label: "CPU per weight estimate (frozen forward), µs",
        better: Better::Lower,
        unit: "Table 1 leave-one-out mean |error| (gf)",
        note: format!(
            "3 → w sigmoid → w ReLU → w sigmoid → 1 sigmoid for w in {WIDTHS:?} (the committed \
             model is w = {HIDDEN}). For each width, the 13 leave-one-out models of Table 1 \
             (seed 000; each trained on the other 12 rows with the committed recipe and seed \
             {}, `force_eval::loo_models`), scored on the row each did not see — the figure \
             docs/learning.md §1 reports for w = {HIDDEN} (this run reproduces the committed \
             metrics.json `table1/loocv` figures at that width). Thirteen rows make this a noisy \
             figure: one or two rows without a neighbour within 10 gf (0, 50, 100 gf) dominate \
             it. Cost: `ForceDnn::estimate_gf` (standardise, frozen forward, decode), median \
             of repeats.",
            force_eval::SEED
        ),
    }
}

/// Table 1 tared, from the workspace at `root`.
pub fn table1(root: &Path) -> Result<Vec<WeightSample>, TradeError> {
    let rows: Vec<(f64, [f64; 3])> =
        paper_fixtures::seed000::table1_weight_in(&root.join("fixtures"))
            .map_err(|e| TradeError::input("Table 1", e))?
            .iter()
            .map(|r| (r.weight_gf, r.pressure_hpa))
            .collect();
    weights::tared_table(&rows).map_err(|e| TradeError::input("Table 1", e))
}

/// One point per width: `(width, mean |LOO error| gf, max |LOO error| gf, µs per estimate)`.
pub fn measure(root: &Path) -> Result<Vec<(usize, f64, f64, f64)>, TradeError> {
    let table = table1(root)?;
    let net = |e| TradeError::input("force DNN", e);
    WIDTHS
        .into_iter()
        .map(|w| {
            let loo = loo_models(&table, force_eval::SEED, false, w).map_err(net)?;
            let errors = error_values(&loo_pairs(&loo, &table).map_err(net)?);
            let get = |k: &str| errors.get(k).copied().unwrap_or(f64::NAN);
            let mut k = 0;
            let cost = median_us(1000, || {
                k = (k + 1) % table.len();
                loo[0].estimate_gf(&table[k].rise_hpa).ok()
            });
            Ok((w, get("mean_abs_error_gf"), get("max_abs_error_gf"), cost))
        })
        .collect()
}

/// The setting label of a width.
pub fn setting(width: usize) -> String {
    format!("{width} hidden per layer")
}

/// The points, and a note with each width's worst row.
pub fn points(root: &Path) -> Result<(Vec<Point>, String), TradeError> {
    let measured = measure(root)?;
    let note = format!(
        "Worst leave-one-out row per width: {}.",
        measured
            .iter()
            .map(|(w, _, max, _)| format!("w = {w}: {max:.1} gf"))
            .collect::<Vec<_>>()
            .join(", ")
    );
    let points = measured
        .into_iter()
        .map(|(w, mean, _, cost)| Point {
            task: TASK,
            knob: "force DNN hidden width".into(),
            setting: setting(w),
            cost_us: cost,
            accuracy: mean,
            pareto: false,
        })
        .collect();
    Ok((points, note))
}
