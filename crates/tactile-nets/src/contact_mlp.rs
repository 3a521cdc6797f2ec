//! The contact-area MLP of seed 000 §4: three pressures (and arrival times) → where on the
//! 4 × 6 pad the fingertip was touched.
//!
//! # Inputs
//! [`N_FEATURES`] raw values per tap, in the order of [`FEATURE_NAMES`], all taken relative to
//! the sensors' own resting baseline (the paper's "1010.xx hPa" initial value):
//! - `rise1..3_hpa`: held pressure minus baseline, hPa (what Table 2 feeds, baseline removed);
//! - `share1..3`: each positive rise over the sum of positive rises (force-free pattern; 1/3
//!   each when nothing rose by 0.01 hPa);
//! - `arrival1..3_ms`: Arrival-of-Time style, each sensor's arrival after the first one to
//!   arrive, ms; [`NO_ARRIVAL_MS`] for a sensor that never rose.
//!
//! The network standardises them with the training set's mean and spread (stored with the
//! weights), then runs hidden layers of 64 and 32 ReLU units, each followed by 30 % dropout
//! (active only in training), trained by Adam with L2 0.001 — the paper's recipe. Inference
//! runs through the network's [`crate::frozen`] copy (no dfdx call per sample).
//!
//! # Heads
//! - [`Head::AverageArea`] (the paper's): one linear output regressing the eq. 4 average-area
//!   label; decoded to the catalogue contact whose label is nearest (ties: the smaller contact,
//!   then the lower mask — eq. 4 labels are not unique across Figure 7's shapes).
//! - [`Head::CellSet`]: 24 sigmoid outputs, one per cell (multi-label cross-entropy on the
//!   tap's cell mask); decoded to the catalogue contact of highest likelihood under independent
//!   cells.
//!
//! The catalogue is the set of distinct contacts (cell masks) in the training split, stored
//! with the weights. Both heads report as region the cell nearest the decoded contact's
//! centroid (ties: the lower row, then column), so `regions` = 24.

use crate::activations::{log_sigmoid, sigmoid};
use crate::error::{NetError, check_output};
use crate::frozen::{self, Freeze, Layer};
use crate::io::TensorFile;
use crate::norm::{mean_and_scale, standardise};
use crate::train::{Loss, Samples, TrainConfig, TrainLog, fit};
use aot_locate::{CELLS, COLS, CellSet, ROWS};
use dfdx::prelude::*;
use hand_traits::{Contact, ContactLocator};
use std::path::Path;

/// What the three sensors read for one tap, the MLP's raw material.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TapReading {
    /// Mean resting pressure before contact, Pa.
    pub baseline_pa: [f32; 3],
    /// Held pressure during contact, Pa.
    pub held_pa: [f32; 3],
    /// Arrival time of each sensor after onset, ms; `None` when it never rose in the window.
    pub arrival_ms: [Option<f32>; 3],
}

impl TapReading {
    /// The reading of a live contact: each sensor's baseline and arrival from `detector`
    /// (arrivals counted from `onset_us`, the contact's onset on the detector's clock) and the
    /// pressures `held_pa` read now. A sensor with no baseline yet reads its own pressure.
    pub fn from_detector(
        detector: &aot_locate::ArrivalDetector,
        held_pa: [f32; 3],
        onset_us: i64,
    ) -> TapReading {
        let ch = detector.channels();
        TapReading {
            baseline_pa: core::array::from_fn(|k| ch[k].baseline_pa().unwrap_or(held_pa[k])),
            held_pa,
            arrival_ms: core::array::from_fn(|k| {
                ch[k].arrival_us().map(|t| (t - onset_us) as f32 / 1000.0)
            }),
        }
    }
}

/// One training example: a reading and the cells that were touched.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactExample {
    /// What the sensors read.
    pub reading: TapReading,
    /// The touched cells (bit `i` = cell `i` of the 4 × 6 pad, [`aot_locate::CellSet`]'s bits);
    /// the [`Head::AverageArea`] target is its eq. 4 label.
    pub mask: u32,
}

/// Eq. 4's label of a mask (0 for an empty or out-of-pad mask, as Table 2's no-contact row).
fn average_area(mask: u32) -> f32 {
    CellSet::from_bits(mask).map_or(0.0, |c| c.average_area().value())
}

/// Raw input values per tap.
pub const N_FEATURES: usize = 9;
/// Names of the raw inputs, in order.
pub const FEATURE_NAMES: [&str; N_FEATURES] = [
    "rise1_hpa",
    "rise2_hpa",
    "rise3_hpa",
    "share1",
    "share2",
    "share3",
    "arrival1_ms",
    "arrival2_ms",
    "arrival3_ms",
];
/// Arrival feature of a sensor that never rose (past the 90 ms series window).
pub const NO_ARRIVAL_MS: f32 = 120.0;
/// Hidden layer widths (seed 000 §4).
pub const HIDDEN: [usize; 2] = [64, 32];
/// Dropout rate after each hidden layer (seed 000 §4).
pub const DROPOUT: f32 = 0.3;
/// L2 regularisation (seed 000 §4).
pub const L2: f64 = 0.001;
/// Label distance at which the regression head's confidence reaches 0 (half a column step).
pub const REGRESSION_CONFIDENCE_SPAN: f32 = 0.05;

type Arch<const O: usize> = (
    (Linear<N_FEATURES, 64>, ReLU, Dropout),
    (Linear<64, 32>, ReLU, Dropout),
    Linear<32, O>,
);
type Net<const O: usize> = <Arch<O> as BuildOnDevice<Cpu, f32>>::Built;
/// The allocation-free inference copy of a [`Net`].
type Fast<const O: usize> = <Net<O> as Freeze>::Frozen;

/// What the network's last layer predicts.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Head {
    /// One output: the eq. 4 average-area value (the paper's label), mean squared error.
    AverageArea,
    /// 24 outputs: one logit per cell of the 4 × 6 pad, sigmoid cross-entropy.
    CellSet,
}

impl Head {
    /// Both heads.
    pub const ALL: [Head; 2] = [Head::AverageArea, Head::CellSet];

    /// File and metrics name: `average_area` or `cell_set`.
    pub fn name(self) -> &'static str {
        match self {
            Head::AverageArea => "average_area",
            Head::CellSet => "cell_set",
        }
    }

    /// The head named `name` ([`Head::name`]).
    pub fn from_name(name: &str) -> Option<Head> {
        Head::ALL.into_iter().find(|h| h.name() == name)
    }

    /// Network outputs.
    pub fn outputs(self) -> usize {
        match self {
            Head::AverageArea => 1,
            Head::CellSet => CELLS,
        }
    }
}

/// The trained network (saved) and its frozen copy (run).
enum Body {
    Area(Net<1>, Fast<1>),
    Cells(Net<CELLS>, Fast<CELLS>),
}

/// A trained contact-area MLP.
pub struct ContactMlp {
    head: Head,
    body: Body,
    mean: [f32; N_FEATURES],
    scale: [f32; N_FEATURES],
    catalogue: Vec<u32>,
}

/// One localisation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Prediction {
    /// The decoded contact: a cell mask from the catalogue.
    pub contact: u32,
    /// The cell nearest the contact's centroid, `0..24`.
    pub region: u16,
    /// `0.0..=1.0`: for [`Head::CellSet`] the contact's share of the likelihood over the
    /// catalogue; for [`Head::AverageArea`] `1 − distance to its label / 0.05`, floored at 0.
    pub confidence: f32,
}

/// The raw input features of one reading ([`FEATURE_NAMES`]).
pub fn features(reading: &TapReading) -> [f32; N_FEATURES] {
    let mut f = [0.0f32; N_FEATURES];
    let rise: [f32; 3] =
        core::array::from_fn(|k| (reading.held_pa[k] - reading.baseline_pa[k]) / 100.0);
    let positive: f32 = rise.iter().map(|r| r.max(0.0)).sum();
    let first = reading
        .arrival_ms
        .iter()
        .flatten()
        .copied()
        .fold(f32::INFINITY, f32::min);
    for k in 0..3 {
        f[k] = rise[k];
        f[3 + k] = if positive > 0.01 {
            rise[k].max(0.0) / positive
        } else {
            1.0 / 3.0
        };
        f[6 + k] = match reading.arrival_ms[k] {
            Some(t) => t - first,
            None => NO_ARRIVAL_MS,
        };
    }
    f
}

/// The training-split contacts: distinct masks, smaller contacts first, then by mask.
fn catalogue_of(examples: &[ContactExample]) -> Vec<u32> {
    let mut masks: Vec<u32> = examples.iter().map(|e| e.mask).collect();
    masks.sort_by_key(|&m| (m.count_ones(), m));
    masks.dedup();
    masks
}

fn build<const O: usize>(dev: &Cpu) -> Net<O> {
    let mut net = dev.build_module::<Arch<O>, f32>();
    net.0.2.p = DROPOUT;
    net.1.2.p = DROPOUT;
    net
}

/// Cell nearest a mask's centroid (ties: the lower row, then column).
fn region_of(mask: u32) -> u16 {
    // CellSet's centroid is 1-based.
    let [r, c] = CellSet::from_bits(mask)
        .and_then(CellSet::centroid)
        .map_or([0.0, 0.0], |[r, c]| [r - 1.0, c - 1.0]);
    let snap = |x: f32, n: usize| ((x - 0.5).ceil().max(0.0) as usize).min(n - 1);
    let (rows, cols) = (usize::from(ROWS), usize::from(COLS));
    (snap(r, rows) * cols + snap(c, cols)) as u16
}

impl ContactMlp {
    /// Trains a model with `head` on `examples` (the training split) using `config`'s epochs,
    /// batch size, learning rate and seeds (its `l2` is the paper's 0.001 unless changed).
    pub fn train(
        examples: &[ContactExample],
        head: Head,
        config: &TrainConfig,
    ) -> Result<(ContactMlp, TrainLog), NetError> {
        if examples.is_empty() {
            return Err(NetError::Training("no training taps".into()));
        }
        let rows: Vec<[f32; N_FEATURES]> = examples.iter().map(|e| features(&e.reading)).collect();
        let (mean, scale) = mean_and_scale(&rows);
        let mut samples = Samples::default();
        for (row, ex) in rows.iter().zip(examples) {
            let z = standardise(row, &mean, &scale);
            match head {
                Head::AverageArea => samples.push(&z, &[average_area(ex.mask)]),
                Head::CellSet => {
                    let bits: [f32; CELLS] =
                        core::array::from_fn(|i| f32::from(u8::from(ex.mask & (1 << i) != 0)));
                    samples.push(&z, &bits);
                }
            }
        }
        let dev = Cpu::seed_from_u64(config.seed);
        let (body, log) = match head {
            Head::AverageArea => {
                let mut net = build::<1>(&dev);
                let log = fit::<_, N_FEATURES, 1>(&dev, &mut net, &samples, Loss::Mse, config)?;
                {
                    let fast = net.freeze()?;
                    (Body::Area(net, fast), log)
                }
            }
            Head::CellSet => {
                let mut net = build::<CELLS>(&dev);
                let loss = Loss::SigmoidCrossEntropy;
                let log = fit::<_, N_FEATURES, CELLS>(&dev, &mut net, &samples, loss, config)?;
                {
                    let fast = net.freeze()?;
                    (Body::Cells(net, fast), log)
                }
            }
        };
        let model = ContactMlp {
            head,
            body,
            mean,
            scale,
            catalogue: catalogue_of(examples),
        };
        Ok((model, log))
    }

    /// The head this model was trained with.
    pub fn head(&self) -> Head {
        self.head
    }

    /// The contacts the decoder chooses from (cell masks).
    pub fn catalogue(&self) -> &[u32] {
        &self.catalogue
    }

    /// The network's raw outputs for raw features (the label value, or 24 cell logits).
    ///
    /// Errors: [`NetError::Shape`] unless `input` has [`N_FEATURES`] values,
    /// [`NetError::NonFinite`] for a NaN or infinite value, [`NetError::NonFiniteOutput`] when
    /// an input far outside the training range overflows the network.
    pub fn outputs(&self, input: &[f32]) -> Result<Vec<f32>, NetError> {
        let (out, n) = self.raw_outputs(input)?;
        Ok(out[..n].to_vec())
    }

    /// [`ContactMlp::outputs`] in a fixed buffer (the first `n` slots hold the head's outputs):
    /// localisation runs inside control cycles, where it must not allocate.
    fn raw_outputs(&self, input: &[f32]) -> Result<([f32; CELLS], usize), NetError> {
        let z: [f32; N_FEATURES] = standardise(&frozen::input(input)?, &self.mean, &self.scale);
        // A finite input can still overflow the standardisation: report it as the overflow it is.
        check_output(&z)?;
        let mut out = [0.0f32; CELLS];
        let n = match &self.body {
            Body::Area(_, fast) => {
                out[..1].copy_from_slice(&fast.forward(z));
                1
            }
            Body::Cells(_, fast) => {
                out = fast.forward(z);
                CELLS
            }
        };
        check_output(&out[..n])?;
        Ok((out, n))
    }

    /// Locates the contact for raw features (see [`ContactMlp::outputs`] for the errors).
    pub fn predict(&self, input: &[f32]) -> Result<Prediction, NetError> {
        let (out, n) = self.raw_outputs(input)?;
        let (contact, confidence) = match self.head {
            Head::AverageArea => self.decode_label(out[0]),
            Head::CellSet => self.decode_cells(&out[..n]),
        }
        .ok_or_else(|| NetError::Training("empty contact catalogue".into()))?;
        Ok(Prediction {
            contact,
            region: region_of(contact),
            confidence,
        })
    }

    fn decode_label(&self, y: f32) -> Option<(u32, f32)> {
        let mut best: Option<(u32, f32)> = None;
        for &m in &self.catalogue {
            let d = (average_area(m) - y).abs();
            if best.is_none_or(|(_, bd)| d < bd) {
                best = Some((m, d));
            }
        }
        best.map(|(m, d)| (m, (1.0 - d / REGRESSION_CONFIDENCE_SPAN).max(0.0)))
    }

    /// The catalogue entry of highest likelihood and its posterior share, in one streaming
    /// log-sum-exp pass (no buffer: this runs in control cycles); `None` for an empty catalogue
    /// or a NaN likelihood. Ties keep the first entry.
    fn decode_cells(&self, logits: &[f32]) -> Option<(u32, f32)> {
        let mut best = (0usize, f32::NEG_INFINITY);
        // Σ_j exp(ll_j − best.1): the posterior of `best` is its inverse.
        let mut sum = 0.0f32;
        for (k, &m) in self.catalogue.iter().enumerate() {
            let ll: f32 = logits
                .iter()
                .enumerate()
                .map(|(i, &z)| {
                    if m & (1 << i) != 0 {
                        log_sigmoid(z)
                    } else {
                        log_sigmoid(-z)
                    }
                })
                .sum();
            if ll.is_nan() {
                return None;
            }
            if ll > best.1 {
                sum = sum * (best.1 - ll).exp() + 1.0;
                best = (k, ll);
            } else if ll == best.1 {
                // Equal (also both −∞): an equal share, as softmax gives it.
                sum += 1.0;
            } else {
                sum += (ll - best.1).exp();
            }
        }
        (sum > 0.0).then(|| (self.catalogue[best.0], 1.0 / sum))
    }

    /// Per-cell contact probabilities (the [`Head::CellSet`] outputs through a sigmoid);
    /// `None` for the regression head.
    pub fn cell_probabilities(&self, input: &[f32]) -> Result<Option<[f32; CELLS]>, NetError> {
        if self.head != Head::CellSet {
            return Ok(None);
        }
        let out = self.outputs(input)?;
        Ok(Some(core::array::from_fn(|i| sigmoid(out[i]))))
    }

    /// Weights, input normalisation and catalogue as a [`TensorFile`].
    pub fn to_file(&self) -> Result<TensorFile, NetError> {
        let mut f = TensorFile::new();
        match &self.body {
            Body::Area(net, _) => f.add_module("net.", net)?,
            Body::Cells(net, _) => f.add_module("net.", net)?,
        }
        f.insert("input.mean", &[N_FEATURES], &self.mean)?;
        f.insert("input.scale", &[N_FEATURES], &self.scale)?;
        // Masks are below 2^24, so f32 holds them exactly.
        let masks: Vec<f32> = self.catalogue.iter().map(|&m| m as f32).collect();
        f.insert("catalogue.masks", &[masks.len()], &masks)?;
        let meta = serde_json::json!({
            "model": "contact_mlp",
            "head": self.head.name(),
            "features": FEATURE_NAMES,
            "hidden": HIDDEN,
            "dropout": DROPOUT,
        });
        f.set_metadata(meta.to_string());
        Ok(f)
    }

    /// A model from [`ContactMlp::to_file`]'s output.
    pub fn from_file(file: &TensorFile) -> Result<ContactMlp, NetError> {
        let meta = file.metadata_json()?;
        let head = meta
            .get("head")
            .and_then(|h| h.as_str())
            .and_then(Head::from_name)
            .ok_or_else(|| NetError::SafeTensors("metadata names no contact-MLP head".into()))?;
        let dev = Cpu::seed_from_u64(0);
        let body = match head {
            Head::AverageArea => {
                let mut net = build::<1>(&dev);
                file.load_module("net.", &mut net)?;
                let fast = net.freeze()?;
                Body::Area(net, fast)
            }
            Head::CellSet => {
                let mut net = build::<CELLS>(&dev);
                file.load_module("net.", &mut net)?;
                let fast = net.freeze()?;
                Body::Cells(net, fast)
            }
        };
        let vec9 = |name: &str| -> Result<[f32; N_FEATURES], NetError> {
            let v = file.get(name, &[N_FEATURES])?;
            Ok(core::array::from_fn(|j| v[j]))
        };
        let masks = file
            .tensor("catalogue.masks")
            .ok_or_else(|| NetError::MissingTensor("catalogue.masks".into()))?;
        let catalogue = masks.data.iter().map(|&m| m as u32).collect();
        Ok(ContactMlp {
            head,
            body,
            mean: vec9("input.mean")?,
            scale: vec9("input.scale")?,
            catalogue,
        })
    }

    /// Writes the model as a `.safetensors` file.
    pub fn save(&self, path: &Path) -> Result<(), NetError> {
        self.to_file()?.save(path)
    }

    /// Reads a model written by [`ContactMlp::save`].
    pub fn load(path: &Path) -> Result<ContactMlp, NetError> {
        Self::from_file(&TensorFile::load(path)?)
    }
}

/// Input: the [`N_FEATURES`] raw features of [`features`]; regions: the 24 cells, row-major.
impl ContactLocator for ContactMlp {
    type Input = [f32];
    type Error = NetError;

    fn locate(&mut self, input: &[f32]) -> Result<Contact, NetError> {
        let p = self.predict(input)?;
        Ok(Contact {
            region: p.region,
            regions: CELLS as u16,
            confidence: p.confidence,
        })
    }
}
