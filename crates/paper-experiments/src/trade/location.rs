//! Contact-location knobs: MS5611 OSR under the fingertip's AoT rules and MLP, the location
//! method (AoT eq. 3 / ranging vs MLP vs CNN) and the CNN's size. Accuracies are recomputed
//! from the committed models and datasets (held-out taps); CPU costs are timed here.

use super::error::TradeError;
use super::pareto::Better;
use super::point::{CostKind, Point, Task};
use super::timing::median_us;
use crate::aot_eval;
use crate::cnn_eval;
use crate::contact_eval::{self, Trained};
use crate::data::fingertip::TapSet;
use crate::data::{fingertip, imu_pad};
use aot_locate::DetectorConfig;
use baro_drivers::{Osr, Scheduler};
use hand_sim::fingertip::geometry::aot_geometry;
use std::path::Path;
use tactile_nets::contact_cnn::{ContactCnn, Variant};
use tactile_nets::contact_mlp::features;

/// Task: 24-area MLP accuracy against the OSR's frame period.
pub const OSR_MLP: &str = "fingertip-osr-mlp";
/// Task: 3 × 3 AoT accuracy against the OSR's frame period.
pub const OSR_AOT: &str = "fingertip-osr-aot";
/// Task: localisation method, CPU per localisation.
pub const METHOD: &str = "contact-location-method";
/// Task: CNN size.
pub const CNN_SIZE: &str = "contact-cnn-size";
/// CPU calls per timing batch.
const CALLS: usize = 200;

const FRAME_COST: &str = "fingertip frame period (3 × MS5611, D2 + D1 at max conversion time), µs — wire / conversion time, not CPU";

/// The tasks of this module.
pub fn tasks() -> Vec<Task> {
    vec![
        Task {
            id: OSR_AOT,
            title: "Fingertip 3 × 3 location (Arrival-of-Time) vs MS5611 OSR",
            cost: CostKind::Wire,
            cost_label: FRAME_COST,
            better: Better::Higher,
            unit: "% correct (3x3 areas)",
            note: "Cost: `Scheduler::cycle_bound_ns` — the three sensors convert in parallel, \
                   D2 then D1, each the datasheet's maximum conversion time (MS5611-01BA03 p. 3), \
                   so one fingertip frame takes 2 × t_conv whatever the sensor count; the CPU is \
                   free meanwhile. Accuracy: `paper_experiments::aot_eval` (the evaluator behind \
                   docs/contact-location.md) on the jittered held-out set of \
                   `fixtures/datasets/fingertip/` (612 taps per OSR shifted off the cell \
                   lattice, so the strict label has no ties), ranging constants fitted on \
                   the lattice set's repeat 0. The lattice set's figures, where a border tap \
                   counts in either area, are in docs/contact-location.md. The dataset was \
                   simulated per OSR (chip noise and sample period of that OSR)."
                .into(),
        },
        Task {
            id: OSR_MLP,
            title: "Fingertip 24-area location (contact MLP) vs MS5611 OSR",
            cost: CostKind::Wire,
            cost_label: FRAME_COST,
            better: Better::Higher,
            unit: "% correct (24 areas)",
            note: "Cost as above. Accuracy: the committed validation-chosen MLP of each OSR \
                   (`crates/tactile-nets/models/contact_mlp/osr*-chosen.safetensors`) re-evaluated by \
                   `contact_eval::load_committed` on that OSR's held-out taps (single-cell \
                   taps, 24-area accuracy as in docs/contact-location.md). Force error per OSR \
                   is not here: the weight series the force DNN is evaluated on was recorded at \
                   OSR 4096 only."
                .into(),
        },
        Task {
            id: METHOD,
            title: "Contact location method: AoT vs MLP vs CNN",
            cost: CostKind::Cpu,
            cost_label: "CPU per localisation, µs",
            better: Better::Higher,
            unit: "% correct (own label set)",
            note: "Not one task: AoT answers 3 × 3 areas and the MLP 24 areas on the \
                   barometric fingertip (each at its best OSR, named in the setting); the CNN \
                   answers 9 regions of the ICM-20789 pad (seed 002) from a 4 × 38 IMU window. \
                   Read the front as 'what each method buys per µs', not as one method \
                   beating another on the same labels. \
                   Cost: one localisation from the already-extracted features (arrival event / \
                   9 MLP features / window), median of repeats; MLP and CNN run their frozen \
                   (plain-array) forward. The MLP's figure is `ContactMlp::predict` with the \
                   chosen cell-set head: the forward plus decoding its 24 cell logits into the \
                   most likely contact of its catalogue (a log-likelihood per catalogue entry), \
                   which dominates the cost."
                .into(),
        },
        Task {
            id: CNN_SIZE,
            title: "Contact CNN size (ICM-20789 pad, 9 regions)",
            cost: CostKind::Cpu,
            cost_label: "CPU per classification, µs",
            better: Better::Higher,
            unit: "% correct (9 regions)",
            note: "The committed variants (`crates/tactile-nets/models/contact_cnn/`, filters and hidden \
                   width in the setting; the paper net trained 1 epoch, ours 6, \
                   `Variant::epochs`), each trained on trial 0 of the all-depth case with \
                   the leak-free tap grouping; accuracy re-evaluated by \
                   `cnn_eval::evaluate_committed` on that held-out split."
                .into(),
        },
    ]
}

fn osr_of(ratio: u16) -> Option<Osr> {
    Osr::ALL.into_iter().find(|o| o.ratio() == ratio)
}

/// A fingertip frame's period at `ratio`, µs (`None` for a ratio the chip has not).
pub fn frame_us(ratio: u16) -> Option<f64> {
    osr_of(ratio).map(|o| Scheduler::new(o).cycle_bound_ns() as f64 / 1e3)
}

/// The AoT evaluator's run over every OSR.
pub(crate) struct AotRun {
    /// `(rule name, osr, percent correct)`, rules in order, OSRs ascending.
    rows: Vec<(&'static str, u16, f64)>,
    report: aot_eval::Report,
    data: fingertip::Dataset,
}

/// The AoT rules' 3 × 3 accuracy per OSR on the jittered held-out set (strict label; ranging
/// fitted on the lattice's repeat 0), and what timing them needs.
pub(crate) fn aot_accuracy(root: &Path) -> Result<AotRun, TradeError> {
    let load =
        |set| fingertip::load_set(root, set).map_err(|e| TradeError::input("fingertip dataset", e));
    let (lattice, data) = (load(TapSet::Lattice)?, load(TapSet::Jittered)?);
    let report =
        aot_eval::evaluate_held_out(&lattice, &data, &aot_geometry(), DetectorConfig::DEFAULT);
    let rows = report
        .by_osr
        .iter()
        .map(|(&(rule, osr), t)| (rule.name(), osr, t.percent()))
        .collect();
    Ok(AotRun { rows, report, data })
}

/// The committed chosen MLPs' held-out 24-area accuracy per OSR, %, with the models.
pub fn mlp_accuracy(root: &Path) -> Result<(Vec<Trained>, Vec<fingertip::TapRecord>), TradeError> {
    let records = fingertip::load(root)
        .map_err(|e| TradeError::input("fingertip dataset", e))?
        .records();
    let models = contact_eval::load_committed(root, &records)
        .map_err(|e| TradeError::input("committed contact MLPs", e))?
        .into_iter()
        .filter(|t| t.kind == contact_eval::Mlp::Chosen)
        .collect();
    Ok((models, records))
}

/// A committed CNN and its re-evaluated held-out accuracy.
pub struct CommittedCnn {
    /// Its variant.
    pub variant: Variant,
    /// Held-out accuracy, %.
    pub percent: f64,
    /// The model.
    pub model: ContactCnn,
}

/// The committed CNNs, re-evaluated on their held-out split.
pub fn cnn_accuracy(root: &Path, taps: &imu_pad::Dataset) -> Result<Vec<CommittedCnn>, TradeError> {
    let mut out = Vec::new();
    for variant in Variant::ALL {
        let (acc, _) =
            cnn_eval::evaluate_committed(root, taps, cnn_eval::Committed::all_depths(variant))
                .map_err(|e| TradeError::input("committed contact CNN", e))?;
        let path = root
            .join(cnn_eval::MODEL_DIR)
            .join(cnn_eval::model_file(variant));
        let model =
            ContactCnn::load(&path).map_err(|e| TradeError::input("committed contact CNN", e))?;
        out.push(CommittedCnn {
            variant,
            percent: 100.0 * acc,
            model,
        });
    }
    Ok(out)
}

/// Setting label of a CNN variant.
pub fn cnn_setting(v: Variant) -> String {
    let (filters, hidden) = v.sizes();
    format!(
        "{} ({filters} filters; {hidden} hidden; {} parameters)",
        v.name(),
        v.parameters()
    )
}

/// Every point of this module's tasks.
pub fn points(root: &Path) -> Result<Vec<Point>, TradeError> {
    let mut out = Vec::new();
    let frame = |osr: u16| {
        frame_us(osr).ok_or_else(|| TradeError::input("fingertip dataset", format!("OSR {osr}")))
    };
    // AoT per OSR, and each rule's best OSR for the method task.
    let AotRun {
        rows: aot,
        report: rep,
        data,
    } = aot_accuracy(root)?;
    for &(rule, osr, pct) in &aot {
        out.push(Point {
            task: OSR_AOT,
            knob: format!("MS5611 OSR; AoT {rule}"),
            setting: format!("OSR {osr}; {rule}"),
            cost_us: frame(osr)?,
            accuracy: pct,
            pareto: false,
        });
    }
    let geometry = aot_geometry();
    for rule in [aot_eval::Rule::Eq3Rise, aot_eval::Rule::Ranging] {
        // The best OSR; the cheapest of equals (the rows run in ascending OSR).
        let best = aot.iter().filter(|r| r.0 == rule.name()).fold(
            None,
            |b: Option<&(&str, u16, f64)>, r| match b {
                Some(b) if b.2 >= r.2 => Some(b),
                _ => Some(r),
            },
        );
        let Some(&(_, osr, pct)) = best else {
            continue;
        };
        let held_out: Vec<_> = data
            .iter()
            .filter(|(t, _)| t.osr == osr)
            .map(|(t, s)| (t, aot_eval::tap_event(t, s, DetectorConfig::DEFAULT)))
            .collect();
        let fit = rep.fits.get(&osr);
        let mut k = 0;
        let cost = median_us(CALLS, || {
            k = (k + 1) % held_out.len().max(1);
            held_out
                .get(k)
                .and_then(|(t, e)| rule.predict(&geometry, fit, t, e))
        });
        out.push(Point {
            task: METHOD,
            knob: "location method".into(),
            setting: format!("AoT {} (fingertip; OSR {osr}; 3x3)", rule.name()),
            cost_us: cost,
            accuracy: pct,
            pareto: false,
        });
    }
    // The MLP per OSR, and its best OSR for the method task.
    let (mlps, records) = mlp_accuracy(root)?;
    for t in &mlps {
        out.push(Point {
            task: OSR_MLP,
            knob: "MS5611 OSR; contact MLP".into(),
            setting: format!("OSR {}", t.osr),
            cost_us: frame(t.osr)?,
            accuracy: 100.0 * t.evaluation.area_accuracy(),
            pareto: false,
        });
    }
    if let Some(best) = mlps.iter().max_by(|a, b| {
        a.evaluation
            .area_accuracy()
            .total_cmp(&b.evaluation.area_accuracy())
    }) {
        let (_, test) = contact_eval::split(&records, best.osr);
        let inputs: Vec<_> = test.iter().map(|r| features(&r.reading)).collect();
        let mut k = 0;
        let cost = median_us(CALLS, || {
            k = (k + 1) % inputs.len().max(1);
            inputs.get(k).map(|x| best.model.predict(x).ok())
        });
        out.push(Point {
            task: METHOD,
            knob: "location method".into(),
            setting: format!(
                "MLP validation-chosen (fingertip; OSR {}; 24 areas)",
                best.osr
            ),
            cost_us: cost,
            accuracy: 100.0 * best.evaluation.area_accuracy(),
            pareto: false,
        });
    }
    // The CNNs: both tasks.
    let taps = imu_pad::load(root).map_err(|e| TradeError::input("ICM pad dataset", e))?;
    for CommittedCnn {
        variant: v,
        percent: pct,
        model,
    } in &cnn_accuracy(root, &taps)?
    {
        let windows: Vec<_> = (0..taps.len())
            .filter_map(|i| taps.window_values(i))
            .collect();
        let mut k = 0;
        let cost = median_us(CALLS, || {
            k = (k + 1) % windows.len().max(1);
            windows.get(k).map(|w| model.predict(w).ok())
        });
        for (task, knob, setting) in [
            (
                METHOD,
                "location method",
                format!("CNN {} (ICM pad; 9 regions)", v.name()),
            ),
            (CNN_SIZE, "CNN filters / hidden width", cnn_setting(*v)),
        ] {
            out.push(Point {
                task,
                knob: knob.into(),
                setting,
                cost_us: cost,
                accuracy: *pct,
                pareto: false,
            });
        }
    }
    Ok(out)
}
