//! The paper's protocol for the softness classifier (seed 001 §3.3–4) on the simulated hand's
//! dataset, its confusion matrices, and the committed models (`crates/tactile-nets/models/softness/`).
//!
//! # Protocol
//! - Train on the `train` set's labelled grasps: the 27 model objects × 5 poses and the 18
//!   household objects (153 grasps). The 6 empty grasps are left out: the paper gives them no
//!   class among its three, and a fourth output would change its 8 → 4 → 4 → 3 network.
//! - Test on `test_regular` (24 objects), `test_irregular` (30 objects) and
//!   `test_irregular_1000` (a fresh draw of 1000 household objects), one grasp each,
//!   each classified from its whole series ([`tactile_nets::softness`]).
//! - Labels: household objects carry the class their fingers' local moduli indicate (the
//!   dataset's `label`, `hand_sim::underactuated::dataset::sensor_class`); the accuracy against
//!   their hidden overall class (`overall`) is reported beside it, with no target.
//! - For each optimiser (LM, Adam) one model per seed in [`SEEDS`]; the *selected* model of an
//!   optimiser is the seed with the lowest training MSE — chosen on training data only.

use crate::data::underactuated::{Grasp, GraspSet, N_VARIABLES};
use hand_traits::{Softness, SoftnessClassifier};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::time::Instant;
use tactile_nets::error::{NetError, RunError};
use tactile_nets::metrics::{MetricsFile, MetricsRow};
use tactile_nets::softness::{CLASSES, SoftnessNet};
use tactile_nets::softness_features::Features;
use tactile_nets::softness_train::{Optimiser, SoftnessTrainConfig, TrainReport, train};

/// Where the committed weights and metrics live, below the workspace root.
pub const MODEL_DIR: &str = "crates/tactile-nets/models/softness";
/// The committed metrics file inside [`MODEL_DIR`].
pub const METRICS_FILE: &str = "metrics.json";
/// Training curves, stop reasons and wall times of the committed run (not drift-checked:
/// times depend on the machine).
pub const TRAINING_FILE: &str = "training.json";
/// Seeds of the committed models.
pub const SEEDS: [u64; 5] = [1, 2, 3, 4, 5];
/// Training rows: every 14th sample (1.4 s apart, 11 per grasp); inference reads every sample.
pub const STRIDE: usize = tactile_nets::softness_features::SERIES_STRIDE;
/// Both optimisers, with their committed settings.
pub const OPTIMISERS: [fn() -> Optimiser; 2] = [Optimiser::lm, Optimiser::adam];

/// A 3 × 3 confusion matrix: `counts[truth][predicted]`, classes in [`Softness::ALL`] order.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Confusion {
    /// Grasps per (true class, predicted class).
    pub counts: [[u32; CLASSES]; CLASSES],
}

impl Confusion {
    /// Adds one classified grasp.
    pub fn add(&mut self, truth: Softness, predicted: Softness) {
        self.counts[truth.index()][predicted.index()] += 1;
    }

    /// Grasps counted.
    pub fn total(&self) -> u32 {
        self.counts.iter().flatten().sum()
    }

    /// Grasps on the diagonal.
    pub fn correct(&self) -> u32 {
        (0..CLASSES).map(|k| self.counts[k][k]).sum()
    }

    /// Fraction correct (0 when empty).
    pub fn accuracy(&self) -> f64 {
        match self.total() {
            0 => 0.0,
            n => f64::from(self.correct()) / f64::from(n),
        }
    }
}

/// The labelled grasps of `set` as (series samples, class) pairs (empty grasps left out); the
/// functions below take them through [`refs`].
pub fn labelled(grasps: &[Grasp], set: GraspSet) -> Vec<(Vec<[f32; N_VARIABLES]>, Softness)> {
    grasps
        .iter()
        .filter(|g| g.set == set)
        .filter_map(|g| Some((g.series.samples(), g.label?)))
        .collect()
}

/// `pairs` with each series borrowed, as the training and evaluation functions take them.
pub fn refs(
    pairs: &[(Vec<[f32; N_VARIABLES]>, Softness)],
) -> Vec<(&[[f32; N_VARIABLES]], Softness)> {
    pairs.iter().map(|(r, l)| (r.as_slice(), *l)).collect()
}

/// Classifies every grasp of `pairs` from its whole series.
pub fn confusion(
    net: &SoftnessNet,
    pairs: &[(&[[f32; N_VARIABLES]], Softness)],
) -> Result<Confusion, NetError> {
    let mut c = Confusion::default();
    for (series, truth) in pairs {
        c.add(*truth, net.predict(series.as_flattened())?);
    }
    Ok(c)
}

/// The f32 network's mean squared error against one-hot targets on the training rows (every
/// [`STRIDE`]-th sample).
pub fn training_mse(
    net: &SoftnessNet,
    pairs: &[(&[[f32; N_VARIABLES]], Softness)],
) -> Result<f64, NetError> {
    rows_mse(|s| net.sample_outputs(s), pairs, STRIDE)
}

/// The mean squared error of `sample_outputs` over every `stride`-th row of `pairs`.
fn rows_mse(
    sample_outputs: impl Fn(&[f32]) -> Result<[f32; CLASSES], RunError>,
    pairs: &[(&[[f32; N_VARIABLES]], Softness)],
    stride: usize,
) -> Result<f64, NetError> {
    let (mut sum, mut n) = (0.0f64, 0usize);
    for (series, truth) in pairs {
        for s in series.iter().step_by(stride.max(1)) {
            let y = sample_outputs(s)?;
            for (k, v) in y.iter().enumerate() {
                let t = if k == truth.index() { 1.0 } else { 0.0 };
                sum += (f64::from(*v) - t).powi(2);
                n += 1;
            }
        }
    }
    Ok(if n == 0 { 0.0 } else { sum / n as f64 })
}

/// One model's evaluation under the protocol.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Evaluation {
    /// On the training grasps.
    pub train: Confusion,
    /// On the 24 regular-shape objects.
    pub regular: Confusion,
    /// On the 30 irregular objects, against their label (what the fingers measure).
    pub irregular: Confusion,
    /// On the 1000 fresh irregular objects, against their label.
    pub irregular_1000: Confusion,
    /// On the 30 irregular objects, against their hidden overall class.
    pub irregular_overall: Confusion,
    /// On the 1000 fresh irregular objects, against their hidden overall class.
    pub irregular_1000_overall: Confusion,
    /// [`training_mse`].
    pub train_mse: f64,
}

impl Evaluation {
    /// Each test set's confusion under its metrics name: `regular`, `irregular`,
    /// `irregular_1000` (labels), `irregular_overall`, `irregular_1000_overall` (hidden class).
    pub fn tests(&self) -> [(&'static str, &Confusion); 5] {
        [
            ("regular", &self.regular),
            ("irregular", &self.irregular),
            ("irregular_1000", &self.irregular_1000),
            ("irregular_overall", &self.irregular_overall),
            ("irregular_1000_overall", &self.irregular_1000_overall),
        ]
    }

    /// The metrics as a row's values: accuracies (`<set>_accuracy`), training MSE and every
    /// confusion count (`regular_cm_soft_hard` = true soft, predicted hard).
    pub fn values(&self) -> BTreeMap<String, f64> {
        let mut v = BTreeMap::from([
            ("train_accuracy".to_owned(), self.train.accuracy()),
            ("train_mse".to_owned(), self.train_mse),
        ]);
        for (set, c) in self.tests() {
            v.insert(format!("{set}_accuracy"), c.accuracy());
            for t in Softness::ALL {
                for p in Softness::ALL {
                    v.insert(
                        format!("{set}_cm_{}_{}", class_name(t), class_name(p)),
                        f64::from(c.counts[t.index()][p.index()]),
                    );
                }
            }
        }
        v
    }
}

/// `soft`, `moderate` or `hard`, as the dataset's `label` column names it.
pub fn class_name(s: Softness) -> &'static str {
    hand_sim::underactuated::dataset::class_name(Some(s))
}

/// Evaluates `net` on the dataset's three sets.
pub fn evaluate(net: &SoftnessNet, grasps: &[Grasp]) -> Result<Evaluation, NetError> {
    evaluate_with(
        |series| net.predict(series),
        |sample| net.sample_outputs(sample),
        grasps,
    )
}

/// Evaluates a classifier given as its `predict` (a whole series, flat) and its
/// `sample_outputs` (one sample's three outputs) — a net's, float or fixed point — as
/// [`evaluate`] does.
pub fn evaluate_with(
    predict: impl Fn(&[f32]) -> Result<Softness, RunError>,
    sample_outputs: impl Fn(&[f32]) -> Result<[f32; CLASSES], RunError>,
    grasps: &[Grasp],
) -> Result<Evaluation, NetError> {
    let train = labelled(grasps, GraspSet::Train);
    scored(
        grasps,
        |g| Ok(predict(g.series.as_flattened())?),
        rows_mse(sample_outputs, &refs(&train), STRIDE)?,
    )
}

/// Classifies every labelled grasp once with `predict` and counts it in its set's confusions,
/// against its label and its hidden overall class.
fn scored(
    grasps: &[Grasp],
    predict: impl Fn(&Grasp) -> Result<Softness, NetError>,
    train_mse: f64,
) -> Result<Evaluation, NetError> {
    let mut e = Evaluation {
        train: Confusion::default(),
        regular: Confusion::default(),
        irregular: Confusion::default(),
        irregular_1000: Confusion::default(),
        irregular_overall: Confusion::default(),
        irregular_1000_overall: Confusion::default(),
        train_mse,
    };
    for g in grasps {
        let (Some(label), Some(overall)) = (g.label, g.overall) else {
            continue;
        };
        let p = predict(g)?;
        match g.set {
            GraspSet::Train => e.train.add(label, p),
            GraspSet::TestRegular => e.regular.add(label, p),
            GraspSet::TestIrregular => {
                e.irregular.add(label, p);
                e.irregular_overall.add(overall, p);
            }
            GraspSet::TestIrregular1000 => {
                e.irregular_1000.add(label, p);
                e.irregular_1000_overall.add(overall, p);
            }
        }
    }
    Ok(e)
}

/// The Bayes rule for the hidden overall class on the household objects of `set`
/// (`hand_sim::underactuated::ceiling`, on each grasp's committed local moduli): the most a
/// classifier of the series can expect for that class. Rows = overall class, columns = the
/// rule's answer.
pub fn bayes_ceiling(grasps: &[Grasp], set: GraspSet) -> Result<Confusion, hand_sim::SimError> {
    let mut c = Confusion::default();
    for g in grasps
        .iter()
        .filter(|g| g.set == set && g.kind == "household")
    {
        if let Some(overall) = g.overall {
            c.add(
                overall,
                hand_sim::underactuated::ceiling::bayes_class(g.local_moduli_pa)?,
            );
        }
    }
    Ok(c)
}

/// The committed recipe for `optimiser` and `seed`.
pub fn recipe(optimiser: Optimiser, seed: u64) -> SoftnessTrainConfig {
    SoftnessTrainConfig {
        optimiser,
        seed,
        stride: STRIDE,
    }
}

/// One trained (or loaded) model.
#[derive(Debug, Clone)]
pub struct Run {
    /// `lm` or `adam`.
    pub optimiser: String,
    /// Its seed.
    pub seed: u64,
    /// The model.
    pub net: SoftnessNet,
    /// Its evaluation.
    pub evaluation: Evaluation,
    /// Training report (`None` for a loaded model).
    pub report: Option<TrainReport>,
    /// Training wall time, s (0 for a loaded model).
    pub seconds: f64,
}

/// File name of a model inside [`MODEL_DIR`].
pub fn model_file(optimiser: &str, seed: u64) -> String {
    format!("{optimiser}-seed{seed}.safetensors")
}

/// Metrics row label of a model.
pub fn row_label(optimiser: &str, seed: u64) -> String {
    format!("{optimiser}/seed{seed}")
}

/// Trains and evaluates one model with [`recipe`].
pub fn train_one(grasps: &[Grasp], optimiser: Optimiser, seed: u64) -> Result<Run, NetError> {
    let pairs = labelled(grasps, GraspSet::Train);
    let start = Instant::now();
    let (net, report) = train(&refs(&pairs), &recipe(optimiser, seed))?;
    let seconds = start.elapsed().as_secs_f64();
    Ok(Run {
        optimiser: optimiser.name().to_owned(),
        seed,
        evaluation: evaluate(&net, grasps)?,
        net,
        report: Some(report),
        seconds,
    })
}

/// Loads every committed model below the workspace root `root` and evaluates it.
pub fn load_committed(root: &Path, grasps: &[Grasp]) -> Result<Vec<Run>, NetError> {
    let dir = root.join(MODEL_DIR);
    let mut out = Vec::new();
    for optimiser in OPTIMISERS.map(|o| o().name()) {
        for seed in SEEDS {
            let net = SoftnessNet::load(&dir.join(model_file(optimiser, seed)))?;
            out.push(Run {
                optimiser: optimiser.to_owned(),
                seed,
                evaluation: evaluate(&net, grasps)?,
                net,
                report: None,
                seconds: 0.0,
            });
        }
    }
    Ok(out)
}

/// The selected run of `optimiser`: lowest training MSE (ties: the lower seed).
pub fn selected<'a>(runs: &'a [Run], optimiser: &str) -> Option<&'a Run> {
    runs.iter()
        .filter(|r| r.optimiser == optimiser)
        .min_by(|a, b| a.evaluation.train_mse.total_cmp(&b.evaluation.train_mse))
}

/// The metrics file of a set of runs: one row per model, and a `selected` row naming the
/// selected seed of each optimiser.
pub fn metrics_file(runs: &[Run]) -> MetricsFile {
    let mut rows: Vec<MetricsRow> = runs
        .iter()
        .map(|r| MetricsRow {
            label: row_label(&r.optimiser, r.seed),
            values: r.evaluation.values(),
        })
        .collect();
    let picks = OPTIMISERS
        .map(|o| o().name())
        .into_iter()
        .filter_map(|o| Some((format!("{o}_seed"), selected(runs, o)?.seed as f64)))
        .collect();
    rows.push(MetricsRow {
        label: "selected".into(),
        values: picks,
    });
    MetricsFile {
        model: "softness".into(),
        description: "Softness classifier (seed 001 §3.3–4), 8 → 4 → 4 → 3 sigmoid / linear, \
                      on the simulated underactuated hand: per optimiser and seed, accuracy on \
                      the training grasps, the 24 regular, the 30 and the 1000 irregular test objects, \
                      training MSE (f32 weights, one-hot targets) and the confusion counts \
                      (`<set>_cm_<true>_<predicted>`); `selected`: the seed of lowest training \
                      MSE per optimiser."
            .into(),
        split: format!(
            "train: 153 labelled grasps of `train` (27 model objects x 5 poses + 18 household; \
             every {STRIDE}th sample); test: test_regular (24), test_irregular (30), test_irregular_1000 (1000), whole \
             series; household objects scored against their label (the class of the median \
             of their fingers' local moduli) and, as `*_overall`, their hidden overall class"
        ),
        seed: SEEDS[0],
        rows,
    }
}

/// Saves every model, the metrics file and the training file into `dir`; returns the paths.
pub fn save_all(dir: &Path, runs: &[Run]) -> Result<Vec<PathBuf>, NetError> {
    std::fs::create_dir_all(dir)?;
    let mut written = Vec::new();
    let mut training = Vec::new();
    for r in runs {
        let path = dir.join(model_file(&r.optimiser, r.seed));
        let stop = r.report.as_ref().map(|t| t.stop.name());
        let meta = serde_json::json!({ "optimiser": r.optimiser, "seed": r.seed,
                                        "stride": STRIDE, "stop": stop });
        r.net.save(&path, meta)?;
        written.push(path);
        if let Some(t) = &r.report {
            // Six significant digits keep the file small and its diffs readable.
            let curve: Vec<f64> = t
                .curve
                .iter()
                .map(|v| format!("{v:.6e}").parse().unwrap_or(*v))
                .collect();
            training.push(serde_json::json!({
                "optimiser": r.optimiser, "seed": r.seed, "stop": t.stop.name(),
                "rows": t.rows, "seconds": (r.seconds * 1000.0).round() / 1000.0,
                "evaluations": t.curve.len(), "mse": t.mse, "curve": curve,
            }));
        }
    }
    let path = dir.join(METRICS_FILE);
    std::fs::write(&path, metrics_file(runs).to_json()?)?;
    written.push(path);
    written.push(write_json(&dir.join(TRAINING_FILE), &training)?);
    Ok(written)
}

/// Writes `value` as pretty JSON (with a final newline) to `path`; returns the path.
fn write_json(path: &Path, value: &impl serde::Serialize) -> Result<PathBuf, NetError> {
    let text = serde_json::to_string_pretty(value).map_err(|e| NetError::Metrics(e.to_string()))?;
    std::fs::write(path, text + "\n")?;
    Ok(path.to_path_buf())
}

/// Our variant: the paper's network (and training) on finger-order-invariant inputs
/// ([`Features`]); classifies a series by the mean output over its feature rows.
#[derive(Debug, Clone, PartialEq)]
pub struct Pooled {
    /// Which inputs.
    pub features: Features,
    /// The 8 → 4 → 4 → 3 network trained on them.
    pub net: SoftnessNet,
}

impl Pooled {
    /// The class of one grasp's series.
    pub fn predict(&self, series: &[[f32; N_VARIABLES]]) -> Result<Softness, NetError> {
        Ok(self
            .net
            .predict(self.features.rows(series).as_flattened())?)
    }
}

/// Input: a grasp's series, flat, [`N_VARIABLES`] readings per sample, as [`SoftnessNet`].
impl SoftnessClassifier for Pooled {
    type Input = [f32];
    type Error = NetError;

    fn classify(&mut self, series: &[f32]) -> Result<Softness, NetError> {
        if series.is_empty() || !series.len().is_multiple_of(N_VARIABLES) {
            return Err(NetError::Shape {
                expected: series.len().div_ceil(N_VARIABLES).max(1) * N_VARIABLES,
                got: series.len(),
            });
        }
        if let Some(index) = series.iter().position(|v| !v.is_finite()) {
            return Err(NetError::NonFinite { index });
        }
        let samples: Vec<[f32; N_VARIABLES]> = series
            .chunks_exact(N_VARIABLES)
            .map(|c| core::array::from_fn(|j| c[j]))
            .collect();
        self.predict(&samples)
    }
}

/// Household training objects our variant adds to the protocol's 153 grasps, drawn
/// at training time by hand-sim ([`hand_sim::underactuated::dataset::household_draw`]) from the
/// dataset's seed, stream [`TRAIN_DRAW`]: as many as the large test draw. The paper's 18 put
/// one object at 5.6 validation points and left the label's boundaries almost without data.
pub const EXTRA_TRAINING: usize = 1000;
/// Stream of the extra training objects.
pub const TRAIN_DRAW: &str = "softness/household-train";
/// Household objects the variant's inputs are chosen on: a draw of their own, stream
/// [`VALIDATION_DRAW`], never trained on; the test sets are never read.
pub const VALIDATION_OBJECTS: usize = 500;
/// Stream of the validation objects.
pub const VALIDATION_DRAW: &str = "softness/household-validation";
/// Seed of the validation trainings.
pub const VALIDATION_SEED: u64 = 1;

/// What our variant trains on: the labelled training grasps of the dataset and of `extra`.
fn training_set<'a>(grasps: &'a [Grasp], extra: &'a [Grasp]) -> Vec<&'a Grasp> {
    grasps
        .iter()
        .chain(extra)
        .filter(|g| g.set == GraspSet::Train && g.label.is_some())
        .collect()
}

/// The labelled grasps of `set` as (feature rows, class).
fn feature_pairs<'a>(
    grasps: impl IntoIterator<Item = &'a Grasp>,
    features: Features,
) -> Vec<(Vec<[f32; N_VARIABLES]>, Softness)> {
    grasps
        .into_iter()
        .filter_map(|g| Some((features.rows(&g.series.samples()), g.label?)))
        .collect()
}

/// Trains the variant with LM and `seed` on `train` grasps.
fn train_pooled(
    fit: &[&Grasp],
    features: Features,
    seed: u64,
) -> Result<(Pooled, TrainReport), NetError> {
    let pairs = feature_pairs(fit.iter().copied(), features);
    let config = SoftnessTrainConfig {
        optimiser: Optimiser::lm(),
        seed,
        stride: features.stride(),
    };
    let (net, report) = train(&refs(&pairs), &config)?;
    Ok((Pooled { features, net }, report))
}

/// Validation accuracy of `features`: trained with LM, seed [`VALIDATION_SEED`], on the
/// labelled training grasps of the dataset and of `extra`, tested on the `validation` objects;
/// the test sets are never read.
pub fn validate_features(
    grasps: &[Grasp],
    extra: &[Grasp],
    validation: &[Grasp],
    features: Features,
) -> Result<f64, NetError> {
    let model = train_pooled(&training_set(grasps, extra), features, VALIDATION_SEED)?.0;
    let mut c = Confusion::default();
    for g in validation {
        let truth = g
            .label
            .ok_or_else(|| NetError::Training("unlabelled validation grasp".into()))?;
        c.add(truth, model.predict(&g.series.samples())?);
    }
    Ok(c.accuracy())
}

/// One trained (or loaded) model of our variant.
#[derive(Debug, Clone)]
pub struct PooledRun {
    /// Its seed.
    pub seed: u64,
    /// The model.
    pub model: Pooled,
    /// Its evaluation (training MSE on the variant's own training rows).
    pub evaluation: Evaluation,
    /// Training report (`None` for a loaded model).
    pub report: Option<TrainReport>,
    /// Training wall time, s (0 for a loaded model).
    pub seconds: f64,
}

/// Evaluates our variant on the dataset's three sets.
pub fn evaluate_pooled(model: &Pooled, grasps: &[Grasp]) -> Result<Evaluation, NetError> {
    let pairs = feature_pairs(
        grasps.iter().filter(|g| g.set == GraspSet::Train),
        model.features,
    );
    scored(
        grasps,
        |g| model.predict(&g.series.samples()),
        rows_mse(
            |s| model.net.sample_outputs(s),
            &refs(&pairs),
            model.features.stride(),
        )?,
    )
}

/// Trains our variant with `features` and `seed` on every labelled training grasp of the
/// dataset and of `extra` (LM, the committed settings) and evaluates it on the dataset
/// (training MSE on the dataset's training grasps, as [`evaluate_pooled`]).
pub fn train_ours(
    grasps: &[Grasp],
    extra: &[Grasp],
    features: Features,
    seed: u64,
) -> Result<PooledRun, NetError> {
    let fit = training_set(grasps, extra);
    let start = Instant::now();
    let (model, report) = train_pooled(&fit, features, seed)?;
    let seconds = start.elapsed().as_secs_f64();
    Ok(PooledRun {
        seed,
        evaluation: evaluate_pooled(&model, grasps)?,
        model,
        report: Some(report),
        seconds,
    })
}

/// Our variant's metrics file inside [`MODEL_DIR`] (drift-checked like [`METRICS_FILE`]).
pub const OURS_METRICS_FILE: &str = "ours_metrics.json";
/// The validation accuracies that chose the variant's inputs (a record of the choice,
/// regenerated by `cargo xtask train softness`; not drift-checked: it retrains).
pub const VALIDATION_FILE: &str = "validation.json";

/// File name of one of our variant's models inside [`MODEL_DIR`].
pub fn ours_file(features: Features, seed: u64) -> String {
    format!("ours-{}-lm-seed{seed}.safetensors", features.name())
}

/// Metrics row label of one of our variant's models.
pub fn ours_label(features: Features, seed: u64) -> String {
    format!("ours/{}/lm/seed{seed}", features.name())
}

/// Our variant's selected run: the seed of lowest training MSE (chosen on training data only).
pub fn selected_ours(runs: &[PooledRun]) -> Option<&PooledRun> {
    runs.iter()
        .min_by(|a, b| a.evaluation.train_mse.total_cmp(&b.evaluation.train_mse))
}

/// The metrics file of our variant's runs: one row per seed and a `selected` row (seed of
/// lowest training MSE).
pub fn ours_metrics_file(runs: &[PooledRun]) -> MetricsFile {
    let mut rows: Vec<MetricsRow> = runs
        .iter()
        .map(|r| MetricsRow {
            label: ours_label(r.model.features, r.seed),
            values: r.evaluation.values(),
        })
        .collect();
    if let Some(best) = selected_ours(runs) {
        rows.push(MetricsRow {
            label: "ours/selected".into(),
            values: BTreeMap::from([("lm_seed".to_owned(), best.seed as f64)]),
        });
    }
    let features = runs.first().map_or("none", |r| r.model.features.name());
    MetricsFile {
        model: "softness-ours".into(),
        description: format!(
            "Our softness variant: the paper's 8 → 4 → 4 → 3 network and LM on the \
             finger-order-invariant inputs `{features}` (tactile_nets::softness_features) and \
             {EXTRA_TRAINING} more household training objects, inputs chosen on \
             {VALIDATION_OBJECTS} household validation objects; per seed, accuracies, training \
             MSE (on the 153 protocol grasps) and confusion counts as metrics.json."
        ),
        split: format!(
            "train: the 153 labelled training grasps and {EXTRA_TRAINING} household objects \
             drawn at training time (hand-sim stream `{TRAIN_DRAW}`); validation: \
             {VALIDATION_OBJECTS} household objects (`{VALIDATION_DRAW}`); test: test_regular \
             (24), test_irregular (30), test_irregular_1000 (1000)"
        ),
        seed: SEEDS[0],
        rows,
    }
}

/// Saves our variant's models, metrics and the validation record into `dir`.
pub fn save_ours(
    dir: &Path,
    runs: &[PooledRun],
    validation: &[(String, f64)],
) -> Result<Vec<PathBuf>, NetError> {
    std::fs::create_dir_all(dir)?;
    let mut written = Vec::new();
    for r in runs {
        let path = dir.join(ours_file(r.model.features, r.seed));
        let meta = serde_json::json!({ "optimiser": "lm", "seed": r.seed,
                                        "features": r.model.features.name(),
                                        "stride": r.model.features.stride() });
        r.model.net.save(&path, meta)?;
        written.push(path);
    }
    let path = dir.join(OURS_METRICS_FILE);
    std::fs::write(&path, ours_metrics_file(runs).to_json()?)?;
    written.push(path);
    let seconds: Vec<f64> = runs
        .iter()
        .map(|r| (r.seconds * 1000.0).round() / 1000.0)
        .collect();
    let record = serde_json::json!({
        "training_objects": EXTRA_TRAINING, "validation_objects": VALIDATION_OBJECTS,
        "seed": VALIDATION_SEED,
        "accuracy": validation.iter().map(|(n, a)| (n.clone(), serde_json::json!(a)))
            .collect::<serde_json::Map<_, _>>(),
        "chosen": runs.first().map(|r| r.model.features.name()),
        "train_seconds": seconds,
    });
    written.push(write_json(&dir.join(VALIDATION_FILE), &record)?);
    Ok(written)
}

/// Loads our variant's committed models below the workspace root `root` and evaluates them;
/// the features are read from the committed metrics file.
pub fn load_ours(root: &Path, grasps: &[Grasp]) -> Result<Vec<PooledRun>, NetError> {
    let dir = root.join(MODEL_DIR);
    let committed = MetricsFile::from_json(&std::fs::read_to_string(dir.join(OURS_METRICS_FILE))?)?;
    let features = Features::ALL
        .into_iter()
        .find(|f| committed.row(&ours_label(*f, SEEDS[0])).is_some())
        .ok_or_else(|| NetError::Metrics("no variant rows in ours_metrics.json".into()))?;
    let mut out = Vec::new();
    for seed in SEEDS {
        let model = Pooled {
            features,
            net: SoftnessNet::load(&dir.join(ours_file(features, seed)))?,
        };
        out.push(PooledRun {
            seed,
            evaluation: evaluate_pooled(&model, grasps)?,
            model,
            report: None,
            seconds: 0.0,
        });
    }
    Ok(out)
}
