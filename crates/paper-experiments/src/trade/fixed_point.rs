//! The models in fixed point against their float models (tactile-nets' `fixed`: Q15 weights,
//! block-floating activations, integer multiply-adds), on the same held-out sets: the contact
//! MLP of each OSR on its held-out taps, the force DNNs on the hand-sim run they did not see
//! and on Table 1, each contact CNN on the held-out windows of its committed split, the
//! softness net on the three test sets of the grasp dataset. What the integer forms save is
//! counted on the Cortex-M3 in docs/embedded.md; here, the accuracy they cost and their host
//! CPU time.

use super::error::TradeError;
use super::force_width::table1;
use super::pareto::Better;
use super::point::{CostKind, Point, Task};
use super::timing::median_us;
use crate::data::underactuated::GraspSet;
use crate::data::{fingertip, imu_pad, underactuated, weights};
use crate::force_eval::{self, error_values};
use crate::softness_eval::{self, Confusion, Evaluation};
use crate::{cnn_eval, contact_eval};
use std::path::Path;
use tactile_nets::contact_cnn::{ContactCnn, Variant};
use tactile_nets::contact_mlp::features;
use tactile_nets::fixed::FixedContactCnn;
use tactile_nets::pretrained::{
    CONTACT_MLP_OSRS, FIXED_SOFTNESS, ForceModel, SOFTNESS, contact_mlp_static,
    fixed_contact_mlp_static,
};

/// Task id: the contact MLP.
pub const MLP: &str = "fixed-point-mlp";
/// Task id: the force DNN.
pub const FORCE: &str = "fixed-point-force";
/// Task id: the contact CNN.
pub const CNN: &str = "fixed-point-cnn";
/// Task id: the softness net.
pub const SOFTNESS_NET: &str = "fixed-point-softness";

/// The four tasks.
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
        Task {
            id: CNN,
            title: "Fixed point vs f32: contact CNN (9 regions)",
            cost: CostKind::Cpu,
            cost_label: "CPU per classification (one 4 × 38 window), µs",
            better: Better::Higher,
            unit: "% correct (9 regions)",
            note: "The committed all-depth CNN of each variant \
                   (`crates/tactile-nets/models/contact_cnn/`) and its fixed-point form, \
                   quantised at run time from it (`FixedContactCnn::quantise`: Q15 weights, \
                   block-floating activations, the 3 × 3 convolution and both dense layers as \
                   `i16 × i16` multiply-adds into `i64`, integer max-pool and ReLUs), both scored \
                   by `cnn_eval::accuracy_with` on the held-out windows of the committed split \
                   (`cnn_eval::held_out`: the evaluation behind the `committed/*` rows of the \
                   CNN's metrics file and the CNN-size task above). Cost: host CPU per window, \
                   standardisation included; the float CNN's kernels use AVX where the CPU has \
                   it, the integer form's are portable."
                .into(),
        },
        Task {
            id: SOFTNESS_NET,
            title: "Fixed point vs f32: softness net (3 classes)",
            cost: CostKind::Cpu,
            cost_label: "CPU per grasp classified (its whole series, 141 samples), µs",
            better: Better::Higher,
            unit: "% correct (3 classes)",
            note: "The built-in softness net (`pretrained::SOFTNESS`, Levenberg–Marquardt, the \
                   seed its metrics file selects) and its fixed-point form \
                   (`pretrained::FIXED_SOFTNESS`, quantised at build time: Q15 weights, the \
                   logistic layers' accumulators read into the table logistic, a grasp's scores \
                   the output layer at the series' mean hidden output, summed in integers), \
                   both scored by `softness_eval::evaluate_with` on the grasp dataset's test \
                   sets against their labels (the sets of the softness metrics file: 24 \
                   regular objects, 30 irregular ones, a fresh draw of 1000). One grasp is \
                   4.2 points of the regular set and 3.3 of the irregular one; compare a set's \
                   two rows (the front across sets compares different sets). Cost: host CPU per \
                   grasp."
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

/// The contact CNN's points: per variant, float and fixed-point accuracy (%) on the held-out
/// windows of its committed split; with `timed`, their CPU cost (else 0).
pub fn cnn_points(root: &Path, timed: bool) -> Result<Vec<Point>, TradeError> {
    let net = |e| TradeError::input("committed contact CNN", e);
    let taps = imu_pad::load(root).map_err(|e| TradeError::input("ICM pad dataset", e))?;
    let mut points = Vec::new();
    for variant in Variant::ALL {
        let which = cnn_eval::Committed::all_depths(variant);
        let float =
            ContactCnn::load(&root.join(cnn_eval::MODEL_DIR).join(which.file())).map_err(net)?;
        let fixed = FixedContactCnn::quantise(&float).map_err(net)?;
        let (data, test) = cnn_eval::held_out(&taps, which);
        let (windows, _) = data.pick(&test);
        let (filters, hidden) = variant.sizes();
        for (is_fixed, accuracy, cost) in [
            (
                false,
                cnn_eval::accuracy_with(|w| float.classify_batch(w), &data, &test).map_err(net)?,
                cycle_cost(timed, &windows, |w| float.predict(w).ok()),
            ),
            (
                true,
                cnn_eval::accuracy_with(|w| fixed.classify_batch(w), &data, &test).map_err(net)?,
                cycle_cost(timed, &windows, |w| fixed.predict(w).ok()),
            ),
        ] {
            points.push(Point {
                task: CNN,
                knob: "number format".into(),
                setting: setting(
                    &format!("{}: {filters} filters; {hidden} hidden", variant.name()),
                    is_fixed,
                ),
                cost_us: cost,
                accuracy: 100.0 * accuracy,
                pareto: false,
            });
        }
    }
    Ok(points)
}

/// The softness net's points: per test set, float and fixed-point accuracy (%) against the
/// labels; with `timed`, their CPU cost per grasp (else 0).
pub fn softness_points(root: &Path, timed: bool) -> Result<Vec<Point>, TradeError> {
    let grasps = underactuated::load(root).map_err(|e| TradeError::input("grasp dataset", e))?;
    let net = |e| TradeError::input("softness net", e);
    let float = softness_eval::evaluate_with(
        |s| SOFTNESS.predict(s),
        |s| SOFTNESS.sample_outputs(s),
        &grasps,
    )
    .map_err(net)?;
    let fixed = softness_eval::evaluate_with(
        |s| FIXED_SOFTNESS.predict(s),
        |s| FIXED_SOFTNESS.sample_outputs(s),
        &grasps,
    )
    .map_err(net)?;
    // Each test set, its name in the metrics file (`Evaluation::tests`) and in the dataset.
    let sets = [
        ("regular", "regular", GraspSet::TestRegular),
        ("irregular", "irregular", GraspSet::TestIrregular),
        (
            "irregular (fresh draw)",
            "irregular_1000",
            GraspSet::TestIrregular1000,
        ),
    ];
    let mut points = Vec::new();
    for (name, key, set) in sets {
        let series: Vec<&[f32]> = grasps
            .iter()
            .filter(|g| g.set == set && g.label.is_some())
            .map(|g| g.series.as_flattened())
            .collect();
        let confusion = |e: &Evaluation| -> Result<Confusion, TradeError> {
            e.tests()
                .into_iter()
                .find(|(k, _)| *k == key)
                .map(|(_, c)| *c)
                .ok_or_else(|| TradeError::input("softness evaluation", format!("no set {key}")))
        };
        for (is_fixed, evaluation) in [(false, &float), (true, &fixed)] {
            let c = confusion(evaluation)?;
            let cost = if is_fixed {
                cycle_cost(timed, &series, |s| FIXED_SOFTNESS.predict(s).ok())
            } else {
                cycle_cost(timed, &series, |s| SOFTNESS.predict(s).ok())
            };
            points.push(Point {
                task: SOFTNESS_NET,
                knob: "number format".into(),
                setting: setting(&format!("{name}: {} grasps", c.total()), is_fixed),
                cost_us: cost,
                accuracy: 100.0 * c.accuracy(),
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
