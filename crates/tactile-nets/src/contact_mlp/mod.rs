//! The contact-area MLP of Kim et al. 2020, §4: three pressures (and arrival times) → where on
//! the 4 × 6 pad the fingertip was touched.
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
//! runs on plain arrays, no ML framework: [`StaticContactMlp`] over the built-in `'static`
//! weights (no `std`), [`ContactMlp`] (feature `std`) over a weights file's; training (feature
//! `train`) freezes dfdx's network into a [`ContactMlp`].
//!
//! # Heads
//! - [`Head::AverageArea`] (the paper's): one linear output regressing the eq. 4 average-area
//!   label; decoded to the catalogue contact whose label is nearest (ties: the smaller contact,
//!   then the lower mask — eq. 4 labels are not unique across Figure 7's shapes).
//! - [`Head::CellSet`]: 24 sigmoid outputs, one per cell (multi-label cross-entropy on the
//!   tap's cell mask); decoded to the catalogue contact of highest likelihood under independent
//!   cells.
//! - [`Head::Centroid`] (ours): two linear outputs regressing the contact's centroid
//!   in cell units ([`ContactExample::centroid`], mean squared error), for contacts anywhere
//!   on the pad rather than on its cell lattice; decoded to the one cell under the point.
//!   Optionally on a [`QuadraticBase`] fitted in closed form first, the network learning
//!   what the base leaves.
//!
//! The catalogue is the set of distinct contacts (cell masks) in the training split, stored
//! with the weights. Every head reports as region the cell nearest the decoded contact's
//! centroid, or under the regressed point (ties: the lower row, then column), so
//! `regions` = 24.

use crate::error::{RunError, check_output};
use crate::frozen::{self, Identity, Layer, Relu, StaticDense};
use crate::norm::standardise;
use aot_locate::{CELLS, COLS, CellSet, ROWS};
use hand_traits::{Contact, ContactLocator};
use num_traits::Float;

mod base;
#[cfg(feature = "std")]
mod model;
#[cfg(feature = "train")]
mod training;
pub use base::{BASE_TERMS, QuadraticBase, base_terms};
#[cfg(feature = "std")]
pub use model::ContactMlp;

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

/// The MLP's inputs of a live pressure stream, frame by frame, as a fingertip computes them:
/// an [`aot_locate::ArrivalDetector`] fed every frame in order ([`push_streaming`]), and once
/// a contact has arrived, each frame's [`features`] of [`TapReading::from_detector`]. A host
/// given the frames a board sampled (their clock and pressures, none lost) rebuilds the
/// board's inputs exactly, so it can run another model on them.
///
/// ```
/// use aot_locate::DetectorConfig;
/// use tactile_nets::contact_mlp::{LiveTap, features};
///
/// let mut tap = LiveTap::new(DetectorConfig::DEFAULT);
/// let rest = [101_000.0; 3];
/// assert!(tap.push(0, rest).is_none());
/// let mut inputs = None;
/// for i in 1..20 {
///     inputs = tap.push(i * 6_000, [101_600.0, 101_300.0, 101_000.0]);
/// }
/// let (_onset, reading) = inputs.expect("arrived");
/// // The inputs: rises in hPa over the resting baseline, shares, arrivals.
/// assert_eq!(&features(&reading)[..3], &[6.0, 3.0, 0.0]);
/// ```
///
/// [`push_streaming`]: aot_locate::ArrivalDetector::push_streaming
#[derive(Debug, Clone)]
pub struct LiveTap {
    detector: aot_locate::ArrivalDetector,
}

impl LiveTap {
    /// Nothing seen yet; arrivals decided by `config`.
    pub fn new(config: aot_locate::DetectorConfig) -> LiveTap {
        LiveTap {
            detector: aot_locate::ArrivalDetector::new(config),
        }
    }

    /// Feeds the frame sampled at `t_us` (strictly later than the last); once a contact has
    /// arrived, returns its onset (µs, on the same clock) and this frame's reading (the MLP's
    /// inputs are its [`features`]).
    pub fn push(&mut self, t_us: i64, pressure_pa: [f32; 3]) -> Option<(i64, TapReading)> {
        let onset = self.detector.push_streaming(t_us, pressure_pa)?;
        Some((
            onset,
            TapReading::from_detector(&self.detector, pressure_pa, onset),
        ))
    }

    /// The detector (its baselines and arrivals, and Arrival-of-Time's event).
    pub fn detector(&self) -> &aot_locate::ArrivalDetector {
        &self.detector
    }
}

/// One training example: a reading, the cells that were touched and where the contact was
/// centred.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactExample {
    /// What the sensors read.
    pub reading: TapReading,
    /// The touched cells (bit `i` = cell `i` of the 4 × 6 pad, [`aot_locate::CellSet`]'s bits);
    /// the [`Head::AverageArea`] target is its eq. 4 label, the [`Head::CellSet`] target the
    /// mask itself.
    pub mask: u32,
    /// The contact's centroid in 1-based (row, column) cell units, cell centres at whole
    /// numbers ([`aot_locate::CellSet::centroid`]; [`aot_locate::AreaGrid::grid_point_of`]
    /// converts pad millimetres): the [`Head::Centroid`] target. A contact pressed off its
    /// cells' centres has it shifted.
    pub centroid: [f32; 2],
}

impl ContactExample {
    /// A contact centred on its cells: the centroid is the mask's (`[0, 0]` for an empty or
    /// out-of-pad mask, which no head can place).
    ///
    /// ```
    /// use tactile_nets::contact_mlp::{ContactExample, TapReading};
    /// let reading = TapReading {
    ///     baseline_pa: [101_000.0; 3],
    ///     held_pa: [101_500.0; 3],
    ///     arrival_ms: [Some(2.0); 3],
    /// };
    /// // Cells 0 and 1: areas 1.1 and 1.2, centred between them.
    /// assert_eq!(ContactExample::new(reading, 0b11).centroid, [1.0, 1.5]);
    /// ```
    pub fn new(reading: TapReading, mask: u32) -> ContactExample {
        let centroid = CellSet::from_bits(mask)
            .and_then(CellSet::centroid)
            .unwrap_or([0.0, 0.0]);
        ContactExample {
            reading,
            mask,
            centroid,
        }
    }
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
/// Hidden layer widths (Kim et al. 2020, §4).
pub const HIDDEN: [usize; 2] = [64, 32];
/// Dropout rate after each hidden layer (Kim et al. 2020, §4).
pub const DROPOUT: f32 = 0.3;
/// L2 regularisation (Kim et al. 2020, §4).
pub const L2: f64 = 0.001;
/// What a contact MLP is built as, beyond its training loop's [`crate::train::TrainConfig`]:
/// what `ContactMlp::train_with` takes (feature `train`). The default is the paper's network.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Options {
    /// Dropout after each hidden layer, `0.0..1.0` (default the paper's [`DROPOUT`]).
    pub dropout: f32,
    /// [`Head::Centroid`] only: the network learns what a [`QuadraticBase`] leaves.
    pub quadratic_base: bool,
    /// [`Head::Centroid`] only: how many networks, each from its own seed, are trained and
    /// averaged (1 to 64; default 1). Why: a regression to fractions of a cell moves with its
    /// seed, and the mean of a few is steadier than any one (on the simulated pad of
    /// docs/contact-location.md, one network placed 95.3–95.8 % of the validation taps over
    /// four seeds, five averaged 96.6 %); it costs one forward pass per member.
    pub members: usize,
}

impl Default for Options {
    fn default() -> Options {
        Options {
            dropout: DROPOUT,
            quadratic_base: false,
            members: 1,
        }
    }
}

/// Label distance at which the regression head's confidence reaches 0 (half a column step).
pub const REGRESSION_CONFIDENCE_SPAN: f32 = 0.05;

/// What the network's last layer predicts.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Head {
    /// One output: the eq. 4 average-area value (the paper's label), mean squared error.
    AverageArea,
    /// 24 outputs: one logit per cell of the 4 × 6 pad, sigmoid cross-entropy.
    CellSet,
    /// 2 outputs: the contact's centroid, (row, column) in cell units, mean squared error.
    Centroid,
}

impl Head {
    /// Every head.
    pub const ALL: [Head; 3] = [Head::AverageArea, Head::CellSet, Head::Centroid];
    /// The heads of the paper's recipe (Kim et al. 2020, §4): its eq. 4 regression, and the
    /// cell-set head that decodes into the same catalogue.
    pub const PAPER: [Head; 2] = [Head::AverageArea, Head::CellSet];

    /// File and metrics name: `average_area`, `cell_set` or `centroid`.
    pub fn name(self) -> &'static str {
        match self {
            Head::AverageArea => "average_area",
            Head::CellSet => "cell_set",
            Head::Centroid => "centroid",
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
            Head::Centroid => 2,
        }
    }
}

/// One localisation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Prediction {
    /// The decoded contact: a cell mask from the catalogue; for [`Head::Centroid`] the one
    /// cell under the regressed point.
    pub contact: u32,
    /// The cell nearest the contact's centroid, `0..24`.
    pub region: u16,
    /// `0.0..=1.0`: for [`Head::CellSet`] the contact's share of the likelihood over the
    /// catalogue; for [`Head::AverageArea`] `1 − distance to its label / 0.05`, floored at 0;
    /// for [`Head::Centroid`] how far inside its cell the point lies: the distance to the
    /// cell's nearest edge over half a cell (1 at the centre, 0 on an edge or off the pad).
    pub confidence: f32,
    /// Where the contact is centred, 1-based (row, column) cell units: the decoded contact's
    /// centroid, or for [`Head::Centroid`] the regressed point.
    pub centroid: [f32; 2],
    /// Whether every standardised input lay within [`Z_RANGE`] training spreads of its training
    /// mean ([`in_range`]); `false`: a reading unlike any the model was trained on.
    pub in_range: bool,
}

/// As a [`Contact`] over the 24 cells, row-major.
impl From<Prediction> for Contact {
    fn from(p: Prediction) -> Contact {
        Contact {
            region: p.region,
            regions: CELLS as u16,
            confidence: p.confidence,
            in_range: p.in_range,
        }
    }
}

/// How far from its training mean, in training spreads, a standardised input may lie and still
/// count as in range: 4. The committed models' training taps lie within 2.6 spreads on every
/// feature at every OSR (their held-out taps too); a press with three times the rises of the
/// hardest training tap lies beyond (both measured in paper-experiments' `nets_contact_mlp`).
pub const Z_RANGE: f32 = 4.0;

/// Whether the standardised inputs `z` lie within [`Z_RANGE`] of the training mean.
pub fn in_range(z: &[f32; N_FEATURES]) -> bool {
    crate::norm::within(z, Z_RANGE)
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

/// A mask's centroid, 1-based (row, column); the top-left cell's centre for an empty mask.
pub(crate) fn centroid_of(mask: u32) -> [f32; 2] {
    CellSet::from_bits(mask)
        .and_then(CellSet::centroid)
        .unwrap_or([1.0, 1.0])
}

/// The cell (`0..24`, row-major) nearest the 1-based (row, column) point `p`: the one holding
/// it, a point off the pad going to the nearest edge cell (ties on a border: the lower row,
/// then column).
pub(crate) fn region_at([r, c]: [f32; 2]) -> u16 {
    // Casts saturate and NaN casts to 0, so any point gives a cell.
    let snap = |x: f32, n: usize| (Float::ceil(x - 1.5).max(0.0) as usize).min(n - 1);
    let (rows, cols) = (usize::from(ROWS), usize::from(COLS));
    (snap(r, rows) * cols + snap(c, cols)) as u16
}

/// How far inside its cell ([`region_at`]) the point `p` lies: the distance to the cell's
/// nearest edge over half a cell, in `0.0..=1.0` (0 off the pad).
fn inside_cell([r, c]: [f32; 2]) -> f32 {
    let depth = |x: f32, n: u8| {
        let edge = 0.5 - Float::abs(x - Float::round(x));
        if (0.5..=f32::from(n) + 0.5).contains(&x) {
            edge
        } else {
            0.0
        }
    };
    (2.0 * depth(r, ROWS).min(depth(c, COLS))).clamp(0.0, 1.0)
}

/// The catalogue contact whose eq. 4 label is nearest `y` and its confidence; the first of
/// equals (smaller contacts come first).
fn decode_label(y: f32, catalogue: impl IntoIterator<Item = u32>) -> Option<(u32, f32)> {
    let mut best: Option<(u32, f32)> = None;
    for m in catalogue {
        let d = (average_area(m) - y).abs();
        if best.is_none_or(|(_, bd)| d < bd) {
            best = Some((m, d));
        }
    }
    best.map(|(m, d)| (m, (1.0 - d / REGRESSION_CONFIDENCE_SPAN).max(0.0)))
}

/// The catalogue entry of highest likelihood under the cell `logits` and its posterior share,
/// in one streaming log-sum-exp pass (no buffer: this runs in control cycles); `None` for an
/// empty catalogue or a NaN likelihood. Ties keep the first entry.
///
/// Under independent cells a mask's log-likelihood is `Σ_i ln σ(±z_i)`, and since
/// `ln σ(z) − ln σ(−z) = z` it equals `Σ_i ln σ(−z_i) + Σ_{i ∈ mask} z_i`. The first sum is the
/// same for every entry and cancels in the argmax and in the posterior (which only reads
/// differences), so an entry scores the sum of its cells' logits: a few adds per entry and one
/// `exp`, where the direct form takes 24 `ln σ` per entry (1 632 per call, ~90 % of the MLP's
/// instructions).
fn decode_cells(logits: &[f32], catalogue: impl IntoIterator<Item = u32>) -> Option<(u32, f32)> {
    let mut best = (0u32, f32::NEG_INFINITY);
    let mut any = false;
    // Σ_j exp(ll_j − best.1): the posterior of `best` is its inverse.
    let mut sum = 0.0f32;
    for m in catalogue {
        let mut ll = 0.0f32;
        let mut bits = m;
        while bits != 0 {
            let i = bits.trailing_zeros() as usize;
            bits &= bits - 1;
            // A bit past the outputs is a cell the network never scores: it cannot be touched.
            ll += logits.get(i).copied().unwrap_or(f32::NEG_INFINITY);
        }
        if ll.is_nan() {
            return None;
        }
        if !any {
            best.0 = m;
            any = true;
        }
        if ll > best.1 {
            sum = sum * Float::exp(best.1 - ll) + 1.0;
            best = (m, ll);
        } else if ll == best.1 {
            // Equal (also both ±∞): an equal share, as softmax gives it.
            sum += 1.0;
        } else {
            sum += Float::exp(ll - best.1);
        }
    }
    (any && sum > 0.0).then_some((best.0, 1.0 / sum))
}

/// The prediction for the network outputs `out` (one label value, a centroid's two
/// coordinates, or [`CELLS`] cell logits) over `catalogue`, in range (the caller, which has
/// the inputs, says otherwise).
fn decode(out: &[f32], catalogue: impl IntoIterator<Item = u32>) -> Result<Prediction, RunError> {
    if let [r, c] = *out {
        let region = region_at([r, c]);
        return Ok(Prediction {
            contact: 1 << region,
            region,
            confidence: inside_cell([r, c]),
            centroid: [r, c],
            in_range: true,
        });
    }
    let (contact, confidence) = if out.len() == 1 {
        decode_label(out[0], catalogue)
    } else {
        decode_cells(out, catalogue)
    }
    .ok_or(RunError::EmptyCatalogue)?;
    let centroid = centroid_of(contact);
    Ok(Prediction {
        contact,
        region: region_at(centroid),
        confidence,
        centroid,
        in_range: true,
    })
}

/// The smallest rise [`Head::Centroid`]'s log scale takes, hPa: a smaller or negative rise (a
/// sensor that felt nothing, read through its noise) counts as this.
pub const LOG_RISE_FLOOR_HPA: f32 = 0.01;

/// What `head`'s network is fed for the raw features `raw` ([`FEATURE_NAMES`]): the same
/// values, except that [`Head::Centroid`] reads the three rises as natural logarithms of hPa
/// (floored at [`LOG_RISE_FLOOR_HPA`]). Why: the pad spreads a load through a Gaussian kernel,
/// so a log rise is quadratic in position and the difference of two is linear; a regression
/// to fractions of a cell needs that precision where the raw rises span 0.1…60 hPa.
pub fn head_inputs(head: Head, raw: [f32; N_FEATURES]) -> [f32; N_FEATURES] {
    let mut x = raw;
    if head == Head::Centroid {
        for r in &mut x[..3] {
            *r = Float::ln(r.max(LOG_RISE_FLOOR_HPA));
        }
    }
    x
}

/// Raw features checked, fed as `head` reads them ([`head_inputs`]) and standardised with the
/// training `mean` and `scale`.
pub(crate) fn standardised(
    head: Head,
    input: &[f32],
    mean: &[f32; N_FEATURES],
    scale: &[f32; N_FEATURES],
) -> Result<[f32; N_FEATURES], RunError> {
    let z = standardise(&head_inputs(head, frozen::input(input)?), mean, scale);
    // A finite input can still overflow the standardisation: report it as the overflow it is.
    check_output(&z)?;
    Ok(z)
}

/// The frozen [`Head::CellSet`] network over `'static` weights.
pub type StaticNet = (
    (StaticDense<N_FEATURES, 64>, Relu, Identity),
    (StaticDense<64, 32>, Relu, Identity),
    StaticDense<32, CELLS>,
);

/// A [`Head::CellSet`] contact MLP whose weights and catalogue are `'static` (the models built
/// into the crate, [`crate::pretrained`]): no allocation, no `std`, weights in flash on a
/// microcontroller. It predicts as [`ContactMlp`] does (feature `std`) with the same weights.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StaticContactMlp {
    net: StaticNet,
    mean: &'static [f32; N_FEATURES],
    scale: &'static [f32; N_FEATURES],
    // As stored in the weights file: masks below 2^24 as f32, exact.
    catalogue: &'static [f32],
}

impl StaticContactMlp {
    /// A model from its network, input standardisation and catalogue (cell masks as `f32`, as
    /// the weights file stores them).
    pub const fn new(
        net: StaticNet,
        mean: &'static [f32; N_FEATURES],
        scale: &'static [f32; N_FEATURES],
        catalogue: &'static [f32],
    ) -> Self {
        Self {
            net,
            mean,
            scale,
            catalogue,
        }
    }

    /// The contacts the decoder chooses from (cell masks).
    pub fn catalogue(&self) -> impl Iterator<Item = u32> + '_ {
        self.catalogue.iter().map(|&m| m as u32)
    }

    /// Locates the contact for the raw features `input` ([`features`]).
    ///
    /// Errors: [`RunError::Shape`] unless `input` has [`N_FEATURES`] values,
    /// [`RunError::NonFinite`] for a NaN or infinite value, [`RunError::NonFiniteOutput`] when
    /// an input far outside the training range overflows the network,
    /// [`RunError::EmptyCatalogue`] for a model without contacts.
    pub fn predict(&self, input: &[f32]) -> Result<Prediction, RunError> {
        let z = standardised(Head::CellSet, input, self.mean, self.scale)?;
        let logits = self.net.forward(z);
        check_output(&logits)?;
        Ok(Prediction {
            in_range: in_range(&z),
            ..decode(&logits, self.catalogue())?
        })
    }
}

/// Input: the [`N_FEATURES`] raw features of [`features`]; regions: the 24 cells, row-major.
impl ContactLocator for StaticContactMlp {
    type Input = [f32];
    type Error = RunError;

    fn locate(&mut self, input: &[f32]) -> Result<Contact, RunError> {
        Ok(self.predict(input)?.into())
    }
}

#[cfg(all(test, feature = "train"))]
mod tests {
    use super::*;
    use crate::activations::log_sigmoid;
    use proptest::prelude::*;

    /// The direct form: `Σ_i ln σ(±z_i)` per entry, then the softmax share of the best.
    fn direct(logits: &[f32], catalogue: &[u32]) -> (u32, f32) {
        let ll: Vec<f64> = catalogue
            .iter()
            .map(|&m| {
                (0..logits.len())
                    .map(|i| {
                        let z = if m & (1 << i) != 0 {
                            logits[i]
                        } else {
                            -logits[i]
                        };
                        f64::from(log_sigmoid(z))
                    })
                    .sum()
            })
            .collect();
        let (k, best) =
            ll.iter().enumerate().fold(
                (0, f64::NEG_INFINITY),
                |b, (k, &v)| if v > b.1 { (k, v) } else { b },
            );
        let sum: f64 = ll.iter().map(|v| (v - best).exp()).sum();
        (catalogue[k], (1.0 / sum) as f32)
    }

    proptest! {
        /// The logit-sum decode picks the entry the direct log-likelihood picks, with the same
        /// posterior, whenever the runner-up is not within rounding of it.
        #[test]
        fn logit_sum_decode_equals_the_direct_likelihood(
            logits in prop::collection::vec(-12.0f32..12.0, CELLS),
            catalogue in prop::collection::btree_set(1u32..(1 << CELLS), 1..80),
        ) {
            let catalogue: Vec<u32> = catalogue.into_iter().collect();
            let (m, p) = decode_cells(&logits, catalogue.iter().copied()).expect("finite");
            let (dm, dp) = direct(&logits, &catalogue);
            // Exact ties aside, the two scores differ only by f32 rounding (~1e-5 here).
            let score = |m: u32| -> f32 {
                (0..CELLS).filter(|i| m & (1 << i) != 0).map(|i| logits[i]).sum()
            };
            prop_assert!(m == dm || (score(m) - score(dm)).abs() < 1e-4, "{m:#x} vs {dm:#x}");
            prop_assert!((p - dp).abs() < 1e-4, "{p} vs {dp}");
        }
    }

    #[test]
    fn a_centroid_decodes_to_the_cell_under_it() {
        let at = |r: f32, c: f32| decode(&[r, c], []).expect("no catalogue needed");
        // Cell 2.3 (index 8) at its centre: fully inside.
        let p = at(2.0, 3.0);
        assert_eq!((p.region, p.contact, p.confidence), (8, 1 << 8, 1.0));
        assert_eq!(p.centroid, [2.0, 3.0]);
        // A quarter cell from its right edge: half as deep.
        let p = at(2.0, 3.25);
        assert_eq!(p.region, 8);
        assert!((p.confidence - 0.5).abs() < 1e-6, "{p:?}");
        // On a border: the lower row / column, and no depth.
        assert_eq!(at(2.5, 3.0).region, 8);
        assert_eq!(at(2.0, 3.5).region, 8);
        assert_eq!(at(2.0, 3.5).confidence, 0.0);
        // Off the pad: the nearest edge cell, no depth; NaN (which `check_output` stops before
        // decoding) still gives a cell.
        let p = at(-3.0, 9.0);
        assert_eq!((p.region, p.confidence), (5, 0.0));
        assert_eq!(at(7.0, 0.2).region, 18);
        assert!(at(f32::NAN, 2.0).region < 24);
        // Catalogue heads report their contact's centroid.
        let mut z = [-9.0f32; CELLS];
        z[0] = 9.0;
        z[1] = 9.0;
        assert_eq!(decode(&z, [1, 0b11]).expect("decodes").centroid, [1.0, 1.5]);
    }

    #[test]
    fn decode_edge_cases() {
        let mut z = [0.0f32; CELLS];
        z[3] = 5.0;
        z[4] = -5.0;
        // {3} beats {4} and {3, 4}; the empty catalogue is None, a NaN logit too.
        assert_eq!(
            decode_cells(&z, [1 << 4, 1 << 3, 3 << 3]).map(|d| d.0),
            Some(1 << 3)
        );
        assert_eq!(decode_cells(&z, []), None);
        z[0] = f32::NAN;
        assert_eq!(decode_cells(&z, [1]), None);
        // Equal scores share the posterior and keep the first entry.
        let z = [1.0f32; CELLS];
        assert_eq!(decode_cells(&z, [1, 2]), Some((1, 0.5)));
        // Huge logits that overflow the sum to +∞ still decode: the +∞ entries share.
        let z = [f32::MAX; CELLS];
        assert_eq!(decode_cells(&z, [0b11, 0b1100, 1]), Some((0b11, 0.5)));
    }
}
