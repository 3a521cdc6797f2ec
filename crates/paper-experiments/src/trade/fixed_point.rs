//! The fingertip's models in fixed point against their float models (tactile-nets' `fixed`:
//! Q15 weights, block-floating activations, integer multiply-adds), on the same held-out sets:
//! the contact MLP of each OSR on its held-out taps, the force DNNs on the hand-sim run they
//! did not see and on Table 1. What the integer forms save is counted on the Cortex-M3 in
//! docs/embedded.md; here, the accuracy they cost and their host CPU time.

use super::error::TradeError;
use super::force_width::table1;
use super::pareto::Better;
use super::point::{CostKind, Point, Task};
use super::timing::median_us;
use crate::contact_eval;
use crate::data::{fingertip, weights};
use crate::force_eval::{self, error_values};
use std::path::Path;
use tactile_nets::contact_mlp::features;
use tactile_nets::pretrained::{
    CONTACT_MLP_OSRS, ForceModel, contact_mlp_static, fixed_contact_mlp_static,
};

/// Task id: the contact MLP.
pub const MLP: &str = "fixed-point-mlp";
/// Task id: the force DNN.
pub const FORCE: &str = "fixed-point-force";

/// The two tasks.
pub fn tasks() -> Vec<Task> {
    vec![
        Task {
            id: MLP,
            title: "Fixed point vs f32: contact MLP (24 areas)",
            cost: CostKind::Cpu,
            cost_label: "CPU per tap (features, network, catalogue decode), µs",
            better: Better::Higher,
            unit: "% correct (24 areas)",
            note:
                "The committed validation-chosen MLP of each OSR (`pretrained::CONTACT_MLP_OSR*`) \
                   and its fixed-point form (`pretrained::FIXED_CONTACT_MLP_OSR*`: Q15 weights, \
                   block-floating activations, integer decode), each evaluated by \
                   `contact_eval::evaluate_with` on that OSR's held-out taps (single-cell taps, \
                   24-area accuracy as in docs/contact-location.md and the OSR task above). \
                   Cost: host CPU per prediction (x86-64 has an FPU; the Cortex-M3, which has \
                   none, is where the integer form pays: docs/embedded.md)."
                    .into(),
        },
        Task {
            id: FORCE,
            title: "Fixed point vs f32: force DNN",
            cost: CostKind::Cpu,
            cost_label: "CPU per weight estimate, µs",
            better: Better::Lower,
            unit: "RMSE (gf)",
            note: "The committed force DNNs (`pretrained::FORCE_DNN_SIM`, `FORCE_DNN_TABLE1`) and \
                   their fixed-point forms (`FIXED_FORCE_DNN_*`): the hand-sim model on its \
                   held-out run (every frame; the `sim/frames` row of its metrics file), the \
                   Table 1 model on the 13 rows it was fitted to (`table1/fit`). Cost: host CPU \
                   per estimate."
                .into(),
        },
    ]
}

/// The setting label of a model form.
pub fn setting(what: &str, fixed: bool) -> String {
    format!("{what} ({})", if fixed { "fixed point" } else { "f32" })
}

/// The contact MLP's points: per OSR, float and fixed-point held-out accuracy (%); with
/// `timed`, their CPU cost (else 0).
pub fn mlp_points(root: &Path, timed: bool) -> Result<Vec<Point>, TradeError> {
    let records = fingertip::load(root)
        .map_err(|e| TradeError::input("fingertip dataset", e))?
        .records();
    let mut points = Vec::new();
    for osr in CONTACT_MLP_OSRS {
        let (Some(float), Some(fixed)) = (contact_mlp_static(osr), fixed_contact_mlp_static(osr))
        else {
            continue;
        };
        let (_, test) = contact_eval::split(&records, osr);
        let net = |e| TradeError::input("contact MLP", e);
        let inputs: Vec<_> = test.iter().map(|r| features(&r.reading)).collect();
        for (is_fixed, evaluation, cost) in [
            (
                false,
                contact_eval::evaluate_with(|x| float.predict(x), &test).map_err(net)?,
                cycle_cost(timed, &inputs, |x| float.predict(x).ok()),
            ),
            (
                true,
                contact_eval::evaluate_with(|x| fixed.predict(x), &test).map_err(net)?,
                cycle_cost(timed, &inputs, |x| fixed.predict(x).ok()),
            ),
        ] {
            points.push(Point {
                task: MLP,
                knob: "number format".into(),
                setting: setting(&format!("OSR {osr}"), is_fixed),
                cost_us: cost,
                accuracy: 100.0 * evaluation.area_accuracy(),
                pareto: false,
            });
        }
    }
    Ok(points)
}

/// The force DNN's points: each model's RMSE (gf), float and fixed point; with `timed`, their
/// CPU cost (else 0).
pub fn force_points(root: &Path, timed: bool) -> Result<Vec<Point>, TradeError> {
    let series = weights::load_series(root).map_err(|e| TradeError::input("weight series", e))?;
    let net = |e| TradeError::input("force DNN", e);
    let (_, held_out) = force_eval::sim_split(&series).map_err(net)?;
    let table = table1(root)?;
    let mut points = Vec::new();
    for (model, what, samples) in [
        (
            ForceModel::Sim,
            "hand-sim model on its held-out run",
            &held_out,
        ),
        (ForceModel::Table1, "Table 1 model on its 13 rows", &table),
    ] {
        let inputs: Vec<[f32; 3]> = samples.iter().map(|s| s.rise_hpa).collect();
        for is_fixed in [false, true] {
            let estimate = |x: &[f32; 3]| {
                if is_fixed {
                    model.fixed_dnn().estimate_gf(x)
                } else {
                    model.dnn().estimate_gf(x)
                }
            };
            let pairs = samples
                .iter()
                .map(|s| Ok((estimate(&s.rise_hpa)?, s.weight_gf)))
                .collect::<Result<Vec<_>, tactile_nets::RunError>>()
                .map_err(|e| net(e.into()))?;
            let rmse = error_values(&pairs)
                .get("rmse_gf")
                .copied()
                .unwrap_or(f64::NAN);
            points.push(Point {
                task: FORCE,
                knob: "number format".into(),
                setting: setting(what, is_fixed),
                cost_us: cycle_cost(timed, &inputs, |x| estimate(x).ok()),
                accuracy: rmse,
                pareto: false,
            });
        }
    }
    Ok(points)
}

/// Median CPU µs of `f` over `inputs` taken in turn (0 unless `timed`).
fn cycle_cost<X, R>(timed: bool, inputs: &[X], f: impl Fn(&X) -> R) -> f64 {
    if !timed {
        return 0.0;
    }
    let mut k = 0;
    median_us(1000, || {
        k = (k + 1) % inputs.len().max(1);
        inputs.get(k).map(&f)
    })
}
