//! Seed 002 §IV-A's protocol for the contact CNN, its committed weights and metrics
//! (`crates/tactile-nets/models/contact_cnn/`).
//!
//! # Augmentation ([`augment`])
//! "The size of the dataset of each contact depth is augmented adding Gaussian noise (30 dB
//! signal-to-noise ratio) from 5 to 105": every tap is kept and gets [`NOISY_COPIES`] = 20
//! noisy copies (5 repeats → 105 windows per position; 8 positions per region → the paper's
//! 840 per region and depth). The noise of each signal (row of the 4 × 38 window) has power
//! `P / 10^(30 / 10)`, `P` the mean square of that signal in that tap — MATLAB's
//! `awgn(x, 30, 'measured')` per signal. Seeded per tap.
//!
//! # Splits ([`Protocol`], [`Grouping`])
//! - 10 trials of a random 80 / 20 split, and 5-fold cross-validation, each on one case: one
//!   depth (0.2…1.6 mm) or all depths together;
//! - [`Grouping::Samples`] (the paper's, as §IV-A reads: the augmented matrices are split):
//!   the noisy copies of one tap land on both sides, so the test set holds near-duplicates of
//!   training windows; [`Grouping::Taps`] (ours, leak-free): whole taps, with their copies, go
//!   to one side.
//!
//! Accuracy is the fraction of held-out windows whose arg-max region is right; a row of the
//! metrics file holds the mean and (n − 1) standard deviation over the trials or folds, in %.

use crate::data::imu_pad::{Dataset, REGIONS, WINDOW_VALUES};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use tactile_nets::contact_cnn::{ContactCnn, Variant, noisy_copies};
use tactile_nets::error::NetError;
use tactile_nets::metrics::{MetricsFile, MetricsRow};
use tactile_nets::train::TrainConfig;

/// Where the committed weights and metrics live, below the workspace root.
pub const MODEL_DIR: &str = "crates/tactile-nets/models/contact_cnn";
/// Frames from the trigger to the centre hand-sim's training windows are cut around (the middle
/// of press + hold + release, `TapTiming::centre_s`), less the ~1 frame the trigger lags the
/// press: where a window must sit to look like the CNN's training data.
pub fn training_centre_frames() -> usize {
    let c = hand_sim::imu_pad::ImuPadConfig::default();
    let t = c.timing;
    let centre_after_press_s = 0.5 * (t.press_s + t.hold_s + t.release_s);
    ((centre_after_press_s * c.sample_rate_hz).round() as usize).saturating_sub(1)
}

/// The committed metrics file inside [`MODEL_DIR`].
pub const METRICS_FILE: &str = "metrics.json";
/// Root seed of the protocol (augmentation, splits, initial weights).
pub const SEED: u64 = 8;
/// The paper's augmentation SNR, dB.
pub const SNR_DB: f32 = 30.0;
/// Noisy copies per tap (5 → 105 per position).
pub const NOISY_COPIES: usize = 20;
/// Random 80 / 20 trials.
pub const TRIALS: usize = 10;
/// Cross-validation folds.
pub const FOLDS: usize = 5;
/// Held-out share of a trial.
pub const TEST_SHARE: f64 = 0.2;

/// Augmented windows with their labels and the tap each came from.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Augmented {
    /// Raw windows (channel-major).
    pub windows: Vec<[f32; WINDOW_VALUES]>,
    /// Region of each window.
    pub regions: Vec<u8>,
    /// Index (into the taps given to [`augment`]) of the tap each window came from.
    pub taps: Vec<usize>,
}

impl Augmented {
    /// The windows and labels at `idx`.
    pub fn pick(&self, idx: &[usize]) -> (Vec<[f32; WINDOW_VALUES]>, Vec<u8>) {
        (
            idx.iter().map(|&i| self.windows[i]).collect(),
            idx.iter().map(|&i| self.regions[i]).collect(),
        )
    }
}

/// Each tap of `data` at `idx` plus `copies` noisy copies at `snr_db` (see the module docs),
/// seeded by `seed`; [`Augmented::taps`] indexes `idx`.
pub fn augment(data: &Dataset, idx: &[usize], copies: usize, snr_db: f32, seed: u64) -> Augmented {
    let mut out = Augmented::default();
    for (t, (tap, window)) in idx
        .iter()
        .filter_map(|&i| Some((data.taps.get(i)?, data.window(i)?)))
        .enumerate()
    {
        // One stream per tap, keyed by what the tap is, so a case's copies do not depend on
        // which other taps are in the case.
        let key =
            (u64::from(tap.depth_um) << 32) | (u64::from(tap.repeat) << 16) | tap.position() as u64;
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        rng.set_stream(key);
        let mut values = [0.0f32; WINDOW_VALUES];
        for (v, w) in values.iter_mut().zip(window.iter()) {
            *v = *w;
        }
        out.windows.push(values);
        out.windows
            .extend(noisy_copies(&values, copies, snr_db, &mut rng));
        out.regions
            .extend(std::iter::repeat_n(tap.region, copies + 1));
        out.taps.extend(std::iter::repeat_n(t, copies + 1));
    }
    out
}

/// Which taps a case trains and tests on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Case {
    /// One contact depth, µm.
    Depth(u32),
    /// Every depth together (Table I's "All cases").
    All,
}

impl Case {
    /// Table I's rows: each depth in `data`, then all.
    pub fn all(data: &Dataset) -> Vec<Case> {
        let mut v: Vec<Case> = data.depths_um().into_iter().map(Case::Depth).collect();
        v.push(Case::All);
        v
    }

    /// `0.2mm` … or `all`.
    pub fn name(self) -> String {
        match self {
            Case::Depth(um) => format!("{:.1}mm", f64::from(um) / 1000.0),
            Case::All => "all".into(),
        }
    }

    /// The indices in `data` of this case's taps.
    pub fn taps(self, data: &Dataset) -> Vec<usize> {
        (0..data.len())
            .filter(|&i| match self {
                Case::Depth(um) => data.taps[i].depth_um == um,
                Case::All => true,
            })
            .collect()
    }

    fn key(self) -> u64 {
        match self {
            Case::Depth(um) => u64::from(um),
            Case::All => u64::from(u32::MAX),
        }
    }
}

/// Repeated random splits or k-fold cross-validation.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Protocol {
    /// [`TRIALS`] random 80 / 20 splits.
    Trials,
    /// [`FOLDS`]-fold cross-validation.
    KFold,
}

impl Protocol {
    /// Both.
    pub const ALL: [Protocol; 2] = [Protocol::Trials, Protocol::KFold];

    /// `trials` or `kfold`.
    pub fn name(self) -> &'static str {
        match self {
            Protocol::Trials => "trials",
            Protocol::KFold => "kfold",
        }
    }

    /// Splits of this protocol.
    pub fn runs(self) -> usize {
        match self {
            Protocol::Trials => TRIALS,
            Protocol::KFold => FOLDS,
        }
    }
}

/// What a split keeps together.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Grouping {
    /// Augmented windows are split one by one (the paper's protocol).
    Samples,
    /// A tap and its noisy copies stay on one side (leak-free).
    Taps,
}

impl Grouping {
    /// `samples` or `taps`.
    pub fn name(self) -> &'static str {
        match self {
            Grouping::Samples => "samples",
            Grouping::Taps => "taps",
        }
    }
}

/// Fisher–Yates with a seeded stream (as [`tactile_nets::train`] does for minibatches).
fn shuffled(n: usize, rng: &mut ChaCha8Rng) -> Vec<usize> {
    let mut v: Vec<usize> = (0..n).collect();
    for i in (1..n).rev() {
        v.swap(i, rng.random_range(0..=i));
    }
    v
}

/// (training, held-out) window indices of run `run` (trial or fold) of `protocol`.
pub fn split(
    data: &Augmented,
    protocol: Protocol,
    grouping: Grouping,
    run: usize,
    seed: u64,
) -> (Vec<usize>, Vec<usize>) {
    let units = match grouping {
        Grouping::Samples => data.windows.len(),
        Grouping::Taps => data.taps.iter().max().map_or(0, |&t| t + 1),
    };
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    // Trials draw a fresh order each run; folds cut one order into FOLDS parts.
    rng.set_stream(match protocol {
        Protocol::Trials => 1 + run as u64,
        Protocol::KFold => 0,
    });
    let order = shuffled(units, &mut rng);
    let (lo, hi) = match protocol {
        Protocol::Trials => (0, (units as f64 * TEST_SHARE).round() as usize),
        Protocol::KFold => (run * units / FOLDS, (run + 1) * units / FOLDS),
    };
    let mut held = vec![false; units];
    for &u in &order[lo..hi] {
        held[u] = true;
    }
    let unit = |i: usize| match grouping {
        Grouping::Samples => i,
        Grouping::Taps => data.taps[i],
    };
    (0..data.windows.len()).partition(|&i| !held[unit(i)])
}

/// Fraction of `idx` that `model` classifies right.
pub fn accuracy(model: &ContactCnn, data: &Augmented, idx: &[usize]) -> Result<f64, NetError> {
    accuracy_with(|w| model.classify_batch(w), data, idx)
}

/// Fraction of `idx` that `classify` (a batch of raw windows → their regions; a model's
/// `classify_batch`, float or fixed point) classifies right.
pub fn accuracy_with(
    classify: impl Fn(&[[f32; WINDOW_VALUES]]) -> Result<Vec<u8>, NetError>,
    data: &Augmented,
    idx: &[usize],
) -> Result<f64, NetError> {
    let (w, r) = data.pick(idx);
    let got = classify(&w)?;
    let hits = got.iter().zip(&r).filter(|(a, b)| a == b).count();
    Ok(hits as f64 / idx.len().max(1) as f64)
}

/// The 9 × 9 confusion counts (`[truth][predicted]`) of `model` on `idx`.
pub fn confusion(
    model: &ContactCnn,
    data: &Augmented,
    idx: &[usize],
) -> Result<[[u32; REGIONS]; REGIONS], NetError> {
    let (w, r) = data.pick(idx);
    let mut m = [[0u32; REGIONS]; REGIONS];
    for (p, t) in model.classify_batch(&w)?.into_iter().zip(r) {
        m[usize::from(t)][usize::from(p)] += 1;
    }
    Ok(m)
}

/// The training recipe of `variant` ([`Variant::epochs`] passes over the augmented windows,
/// each tap seen 21 times per pass); `label` names the progress bar.
pub fn recipe(variant: Variant, seed: u64, label: String) -> TrainConfig {
    TrainConfig {
        epochs: variant.epochs(),
        batch_size: 32,
        learning_rate: 1e-3,
        l2: 0.0,
        seed,
        progress: false,
        label,
    }
}

/// The seed of one training run, from the root seed and what the run is.
pub fn run_seed(seed: u64, case: Case, protocol: Protocol, grouping: Grouping, run: usize) -> u64 {
    let tag = (case.key() << 8) ^ ((protocol as u64) << 4) ^ ((grouping as u64) << 6) ^ run as u64;
    seed.wrapping_mul(0x9e37_79b9_7f4a_7c15) ^ tag
}

/// One job of the protocol: a model trained and tested on one split.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Job {
    /// Which network.
    pub variant: Variant,
    /// Which taps.
    pub case: Case,
    /// Trials or folds.
    pub protocol: Protocol,
    /// Samples or taps.
    pub grouping: Grouping,
    /// Trial / fold index.
    pub run: usize,
}

/// Trains and tests one job; returns the held-out accuracy and the model.
pub fn run_job(
    job: Job,
    data: &Augmented,
    seed: u64,
    adjust: &dyn Fn(&mut TrainConfig),
) -> Result<(f64, ContactCnn), NetError> {
    let (train, test) = split(data, job.protocol, job.grouping, job.run, seed);
    let (w, r) = data.pick(&train);
    let s = run_seed(seed, job.case, job.protocol, job.grouping, job.run);
    let mut config = recipe(job.variant, s, String::new());
    adjust(&mut config);
    let (model, _) = ContactCnn::train(&w, &r, job.variant, &config)?;
    Ok((accuracy(&model, data, &test)?, model))
}

/// Mean and (n − 1) standard deviation, in %.
pub fn mean_std_pct(acc: &[f64]) -> (f64, f64) {
    let n = acc.len() as f64;
    let mean = acc.iter().sum::<f64>() / n.max(1.0);
    let var = acc.iter().map(|a| (a - mean).powi(2)).sum::<f64>() / (n - 1.0).max(1.0);
    (100.0 * mean, 100.0 * var.sqrt())
}

/// Metrics row label of a protocol result.
pub fn row_label(variant: Variant, grouping: Grouping, protocol: Protocol, case: Case) -> String {
    format!(
        "{}/{}/{}/{}",
        variant.name(),
        grouping.name(),
        protocol.name(),
        case.name()
    )
}

/// Metrics row label of the committed all-depth model of `variant`.
pub fn committed_label(variant: Variant) -> String {
    Committed::all_depths(variant).label()
}

/// A committed model: `variant` trained on trial 0 of `case`, leak-free grouping — the split a
/// test re-creates to check the weights against the metrics.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Committed {
    /// Which network.
    pub variant: Variant,
    /// Which taps it learnt from (its trial 0's training share).
    pub case: Case,
}

impl Committed {
    /// `variant` trained on every depth (Table I's "All cases").
    pub const fn all_depths(variant: Variant) -> Committed {
        Committed {
            variant,
            case: Case::All,
        }
    }

    /// The protocol job that trains it.
    pub fn job(self) -> Job {
        Job {
            variant: self.variant,
            case: self.case,
            protocol: Protocol::Trials,
            grouping: Grouping::Taps,
            run: 0,
        }
    }

    /// Its file name inside [`MODEL_DIR`]: `paper.safetensors` for all depths,
    /// `paper-1.2mm.safetensors` for one.
    pub fn file(self) -> String {
        match self.case {
            Case::All => format!("{}.safetensors", self.variant.name()),
            Case::Depth(_) => format!("{}-{}.safetensors", self.variant.name(), self.case.name()),
        }
    }

    /// Its metrics row label: `committed/paper`, `committed/paper/1.2mm`.
    pub fn label(self) -> String {
        match self.case {
            Case::All => format!("committed/{}", self.variant.name()),
            Case::Depth(_) => format!("committed/{}/{}", self.variant.name(), self.case.name()),
        }
    }
}

/// The real-time test's contact depth (seed 002 §IV-B), µm.
pub const REALTIME_DEPTH_UM: u32 = 1200;

/// The model of the real-time tap runs: the paper net trained on the taps of
/// [`REALTIME_DEPTH_UM`], as the paper's real-time test (seed 002 §V: "Contact location
/// recognition in real-time was performed using a robot arm and the CNN trained with data from
/// 1.2 mm contact depth"). Chosen by that sentence, before any tap run had used it.
pub const REALTIME: Committed = Committed {
    variant: Variant::Paper,
    case: Case::Depth(REALTIME_DEPTH_UM),
};

/// Every committed model: each variant on all depths, and [`REALTIME`].
pub const COMMITTED: [Committed; 4] = [
    Committed::all_depths(Variant::Paper),
    Committed::all_depths(Variant::Small),
    Committed::all_depths(Variant::Wide),
    REALTIME,
];

/// File name of the committed all-depth model of `variant` inside [`MODEL_DIR`].
pub fn model_file(variant: Variant) -> String {
    Committed::all_depths(variant).file()
}

/// Re-evaluates the committed model `which` below the workspace root `root` on its held-out
/// split: (accuracy, confusion counts).
pub fn evaluate_committed(
    root: &Path,
    taps: &Dataset,
    which: Committed,
) -> Result<(f64, [[u32; REGIONS]; REGIONS]), NetError> {
    let model = ContactCnn::load(&root.join(MODEL_DIR).join(which.file()))?;
    let (data, test) = held_out(taps, which);
    Ok((
        accuracy(&model, &data, &test)?,
        confusion(&model, &data, &test)?,
    ))
}

/// The augmented windows of the committed model `which`'s case and the indices of its
/// held-out split (the windows [`evaluate_committed`] scores it on).
pub fn held_out(taps: &Dataset, which: Committed) -> (Augmented, Vec<usize>) {
    let job = which.job();
    let data = augment(taps, &job.case.taps(taps), NOISY_COPIES, SNR_DB, SEED);
    let (_, test) = split(&data, job.protocol, job.grouping, job.run, SEED);
    (data, test)
}

/// The committed-model rows: accuracy and the confusion counts (`c{truth}{predicted}`).
pub fn committed_row(
    which: Committed,
    accuracy: f64,
    confusion: &[[u32; REGIONS]; REGIONS],
) -> MetricsRow {
    let mut values = BTreeMap::from([("accuracy".to_owned(), accuracy)]);
    for (t, row) in confusion.iter().enumerate() {
        for (p, &n) in row.iter().enumerate() {
            values.insert(format!("c{t}{p}"), f64::from(n));
        }
    }
    MetricsRow {
        label: which.label(),
        values,
    }
}

/// A protocol result row: mean and standard deviation of accuracy, %, and the runs.
pub fn protocol_row(label: String, accuracies: &[f64]) -> MetricsRow {
    let (mean, std) = mean_std_pct(accuracies);
    MetricsRow {
        label,
        values: BTreeMap::from([
            ("mean_pct".to_owned(), mean),
            ("std_pct".to_owned(), std),
            ("runs".to_owned(), accuracies.len() as f64),
        ]),
    }
}

/// The metrics file around `rows`.
pub fn metrics_file(rows: Vec<MetricsRow>, seed: u64) -> MetricsFile {
    MetricsFile {
        model: "contact_cnn".into(),
        description: "Contact CNN (seed 002 §IV-A) on the hand-sim ICM-20789 pad taps, 30 dB \
                      augmentation (1 + 20 windows per tap). Rows `variant/grouping/protocol/case`: \
                      held-out accuracy mean and (n-1) std over 10 random 80/20 trials or 5 folds, \
                      %. Rows `committed/variant`: the committed weights on their held-out split \
                      (accuracy, confusion counts c{truth}{predicted})."
            .into(),
        split: "grouping `samples`: augmented windows split one by one (paper); `taps`: a tap \
                and its noisy copies on one side (leak-free); committed models: all depths \
                (and the paper net at 1.2 mm, the real-time test's depth), taps grouping, trial 0"
            .into(),
        seed,
        rows,
    }
}

/// Writes the metrics file into `dir`; returns its path.
pub fn save_metrics(dir: &Path, file: &MetricsFile) -> Result<PathBuf, NetError> {
    std::fs::create_dir_all(dir)?;
    let path = dir.join(METRICS_FILE);
    std::fs::write(&path, file.to_json()?)?;
    Ok(path)
}
