//! The softness classifier of the underactuated-hand softness paper ("Distinguish the Textures
//! of Grasped Objects…"), §3.3: an 8 → 4 → 4 → 3 network (two hidden layers of 4
//! logistic-sigmoid neurons, a linear "purelin" output), run on plain `f32` arrays (feature
//! `std` loads weights files; without it, the built-in nets in `'static` arrays), trained by
//! Levenberg–Marquardt (feature `train`: `softness_train`).
//!
//! # Feature vector
//! One network input is **one sample of the grasp's series**: the paper's 8 variables (§3.1)
//! read at the same instant, in this order —
//! `[f1_n, f2_n, f3_n, f4_n, a1_deg, a2_deg, a3_deg, a4_deg]`: the four FSR forces (N) and the
//! four distal joint angles (degrees), fingers 1–4 ([`VARIABLE_NAMES`]). A grasp's series runs
//! at 10 Hz from first contact `t₁` to `t₁ + 14 s` (141 samples). Each variable is mapped to
//! `[-1, 1]` with the training set's minimum and maximum (Matlab's `mapminmax`, the default
//! input processing of the toolbox the paper used), then clipped to `±`[`INPUT_CLIP`].
//!
//! # Output and decision
//! Three linear outputs, one per class in [`Softness::ALL`] order (soft, moderate, hard),
//! trained towards one-hot targets by least squares. A grasp is classified by the **mean of
//! the per-sample outputs over its whole series**; the largest mean wins (ties: the softer
//! class).
//!
//! ```
//! # #[cfg(feature = "train")] {
//! use hand_traits::{Softness, SoftnessClassifier};
//! use tactile_nets::softness::SoftnessNet;
//! use tactile_nets::softness_train::{Optimiser, SoftnessTrainConfig, train};
//!
//! // Two toy "grasps": a soft one (low force, closed fingers) and a hard one.
//! let soft = vec![[0.5, 0.4, 0.6, 0.5, 85.0, 86.0, 84.0, 85.0]; 5];
//! let hard = vec![[30.0, 31.0, 29.0, 30.0, 25.0, 24.0, 26.0, 25.0]; 5];
//! let grasps = [(soft.as_slice(), Softness::Soft), (hard.as_slice(), Softness::Hard)];
//! let config = SoftnessTrainConfig { optimiser: Optimiser::lm(), seed: 1, stride: 1 };
//! let (mut net, _report) = train(&grasps, &config)?;
//! let series: Vec<f32> = hard.concat();
//! assert_eq!(net.classify(&series)?, Softness::Hard);
//! assert!(net.classify(&series[..7]).is_err()); // not whole samples: a typed error
//! # }
//! # Ok::<(), tactile_nets::NetError>(())
//! ```

use crate::error::{RunError, check_input, check_output};
#[cfg(feature = "std")]
use crate::{error::NetError, io::TensorFile};
use hand_traits::{Softness, SoftnessClassifier};
#[cfg(feature = "std")]
use std::path::Path;

/// Readings per sample: `f1_n..f4_n`, then `a1_deg..a4_deg` (the paper's 8 variables, §3.1).
pub const N_VARIABLES: usize = 8;
/// Names of the 8 variables, in sample order.
pub const VARIABLE_NAMES: [&str; N_VARIABLES] = [
    "f1_n", "f2_n", "f3_n", "f4_n", "a1_deg", "a2_deg", "a3_deg", "a4_deg",
];

/// Neurons per hidden layer (the paper's §3.3: two hidden layers of four).
pub const HIDDEN: usize = 4;
/// Classes (soft, moderate, hard).
pub const CLASSES: usize = 3;
// The network's outputs are the classes in `Softness::ALL` order.
const _: () = assert!(Softness::ALL.len() == CLASSES);
/// Trainable parameters: `8·4 + 4 + 4·4 + 4 + 4·3 + 3`.
pub const N_PARAMS: usize =
    N_VARIABLES * HIDDEN + HIDDEN + HIDDEN * HIDDEN + HIDDEN + HIDDEN * CLASSES + CLASSES;
/// Normalised inputs are clipped to `±INPUT_CLIP`: the training range is `[-1, 1]`, so this
/// only bites 50 training ranges away, where every hidden sigmoid is saturated; it keeps the
/// outputs finite for any finite input.
pub const INPUT_CLIP: f32 = 100.0;

/// How far past its training range a reading may lie and still count as inside it, as a share
/// of the variable's training span on each side (normalised, `|z| ≤ 1.2`): a grasp of a new
/// object reads a little past the training extremes; far past them the network extrapolates.
pub const RANGE_MARGIN: f32 = 0.1;

/// Input scaling: `z = clip(gain · (x − min) − 1)`, `gain = 2 / (max − min)` (0 for a
/// variable that never varied in training, which then always reads −1).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InputScale {
    /// Per-variable training minimum.
    pub min: [f32; N_VARIABLES],
    /// Per-variable `2 / (max − min)`.
    pub gain: [f32; N_VARIABLES],
}

impl InputScale {
    /// Fits the scale to the samples' per-variable minimum and maximum.
    pub fn fit<'a>(samples: impl IntoIterator<Item = &'a [f32; N_VARIABLES]>) -> InputScale {
        let mut lo = [f32::INFINITY; N_VARIABLES];
        let mut hi = [f32::NEG_INFINITY; N_VARIABLES];
        for s in samples {
            for j in 0..N_VARIABLES {
                lo[j] = lo[j].min(s[j]);
                hi[j] = hi[j].max(s[j]);
            }
        }
        let min = core::array::from_fn(|j| if lo[j].is_finite() { lo[j] } else { 0.0 });
        let gain = core::array::from_fn(|j| {
            let span = hi[j] - lo[j];
            if span.is_finite() && span > 0.0 {
                2.0 / span
            } else {
                0.0
            }
        });
        InputScale { min, gain }
    }

    /// Each variable's training range, `[min, max]`.
    pub fn range(&self) -> [[f32; 2]; N_VARIABLES] {
        core::array::from_fn(|j| {
            let span = if self.gain[j] > 0.0 {
                2.0 / self.gain[j]
            } else {
                0.0
            };
            [self.min[j], self.min[j] + span]
        })
    }

    /// How many readings of one raw sample lie outside their training range widened by
    /// [`RANGE_MARGIN`]; a variable that never varied in training counts when it reads
    /// anything else.
    pub fn outside(&self, x: &[f32; N_VARIABLES]) -> usize {
        (0..N_VARIABLES)
            .filter(|&j| {
                if self.gain[j] > 0.0 {
                    let z = self.gain[j] * (x[j] - self.min[j]) - 1.0;
                    // A NaN (which a model's input check refuses first) counts as outside.
                    z.is_nan() || z.abs() > 1.0 + 2.0 * RANGE_MARGIN
                } else {
                    x[j] != self.min[j]
                }
            })
            .count()
    }

    /// The normalised input of one raw sample (finite for finite input).
    #[inline]
    pub fn apply(&self, x: &[f32; N_VARIABLES]) -> [f32; N_VARIABLES] {
        core::array::from_fn(|j| {
            // (x − min) may overflow to ±∞ for huge x; the clip brings it back.
            (self.gain[j] * (x[j] - self.min[j]) - 1.0).clamp(-INPUT_CLIP, INPUT_CLIP)
        })
    }
}

/// A trained softness classifier: weights (f32, row-major: outputs × inputs) and input
/// scaling.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SoftnessNet {
    w1: [[f32; N_VARIABLES]; HIDDEN],
    b1: [f32; HIDDEN],
    w2: [[f32; HIDDEN]; HIDDEN],
    b2: [f32; HIDDEN],
    w3: [[f32; HIDDEN]; CLASSES],
    b3: [f32; CLASSES],
    scale: InputScale,
}

/// `W x + b`, one row of `W` per output, summed in input order.
// Plain loops, inlined: through `array::from_fn` and a `fold` the compiler stopped inlining
// the sums once other forms of the net shared the module (+29 % instructions per sample).
#[inline(always)]
fn affine<const I: usize, const O: usize>(
    w: &[[f32; I]; O],
    b: &[f32; O],
    x: &[f32; I],
) -> [f32; O] {
    let mut y = *b;
    for (y, row) in y.iter_mut().zip(w) {
        let mut acc = 0.0f32;
        for (w, x) in row.iter().zip(x) {
            acc += w * x;
        }
        *y += acc;
    }
    y
}

/// The logistic sigmoid `1 / (1 + e^-z)`: `e^-z` may overflow to `+∞`, which gives 0, so the
/// result stays in `[0, 1]` for every non-NaN `z`.
fn logistic(z: f32) -> f32 {
    1.0 / (1.0 + num_traits::Float::exp(-z))
}

impl SoftnessNet {
    /// A classifier from its layers (row-major, outputs × inputs) and input scaling.
    pub const fn new(
        w1: [[f32; N_VARIABLES]; HIDDEN],
        b1: [f32; HIDDEN],
        w2: [[f32; HIDDEN]; HIDDEN],
        b2: [f32; HIDDEN],
        w3: [[f32; HIDDEN]; CLASSES],
        b3: [f32; CLASSES],
        scale: InputScale,
    ) -> SoftnessNet {
        SoftnessNet {
            w1,
            b1,
            w2,
            b2,
            w3,
            b3,
            scale,
        }
    }

    /// A classifier from its flat parameters — `w1` row-major (4 × 8), `b1`, `w2` row-major
    /// (4 × 4), `b2`, `w3` row-major (3 × 4), `b3`: [`N_PARAMS`] values — and its input
    /// scaling; `None` for another count.
    pub fn from_flat(p: &[f32], scale: InputScale) -> Option<SoftnessNet> {
        if p.len() != N_PARAMS {
            return None;
        }
        let mut k = 0;
        let mut take = |n: usize| {
            k += n;
            &p[k - n..k]
        };
        fn rows<const I: usize, const O: usize>(v: &[f32]) -> [[f32; I]; O] {
            core::array::from_fn(|o| core::array::from_fn(|i| v[o * I + i]))
        }
        fn vector<const N: usize>(v: &[f32]) -> [f32; N] {
            core::array::from_fn(|i| v[i])
        }
        Some(SoftnessNet {
            w1: rows(take(HIDDEN * N_VARIABLES)),
            b1: vector(take(HIDDEN)),
            w2: rows(take(HIDDEN * HIDDEN)),
            b2: vector(take(HIDDEN)),
            w3: rows(take(CLASSES * HIDDEN)),
            b3: vector(take(CLASSES)),
            scale,
        })
    }

    /// The flat parameters ([`SoftnessNet::from_flat`]'s order).
    pub fn flat(&self) -> [f32; N_PARAMS] {
        let mut out = [0.0; N_PARAMS];
        let parts = [
            self.w1.as_flattened(),
            &self.b1,
            self.w2.as_flattened(),
            &self.b2,
            self.w3.as_flattened(),
            &self.b3,
        ];
        for (o, v) in out.iter_mut().zip(parts.into_iter().flatten()) {
            *o = *v;
        }
        out
    }

    /// The input scaling.
    pub fn scale(&self) -> &InputScale {
        &self.scale
    }

    /// The three linear outputs of a normalised sample.
    fn forward(&self, z: &[f32; N_VARIABLES]) -> [f32; CLASSES] {
        let h1 = affine(&self.w1, &self.b1, z).map(logistic);
        let h2 = affine(&self.w2, &self.b2, &h1).map(logistic);
        affine(&self.w3, &self.b3, &h2)
    }

    /// The three linear outputs for one raw sample of [`N_VARIABLES`] readings.
    ///
    /// Errors: [`RunError::Shape`] unless `sample` has 8 values, [`RunError::NonFinite`] for a
    /// NaN or infinite reading.
    pub fn sample_outputs(&self, sample: &[f32]) -> Result<[f32; CLASSES], RunError> {
        check_input(sample, N_VARIABLES)?;
        let x: [f32; N_VARIABLES] = core::array::from_fn(|j| sample[j]);
        let out = self.forward(&self.scale.apply(&x));
        check_output(&out)?;
        Ok(out)
    }

    /// Mean outputs over a series given flat, [`N_VARIABLES`] readings per sample.
    ///
    /// Errors: [`RunError::Shape`] when the series is empty or not whole samples (`expected`
    /// is then the next whole length), [`RunError::NonFinite`] at the first bad reading.
    pub fn scores(&self, series: &[f32]) -> Result<[f32; CLASSES], RunError> {
        let mut sum = [0.0f64; CLASSES];
        for (i, sample) in samples(series)?.enumerate() {
            let y = self.sample_outputs(sample).map_err(|e| in_series(e, i))?;
            for k in 0..CLASSES {
                sum[k] += f64::from(y[k]);
            }
        }
        let n = (series.len() / N_VARIABLES) as f64;
        Ok(core::array::from_fn(|k| (sum[k] / n) as f32))
    }

    /// The class of a series ([`SoftnessNet::scores`]'s largest mean; ties: the softer).
    pub fn predict(&self, series: &[f32]) -> Result<Softness, RunError> {
        Ok(class_of(&self.scores(series)?))
    }

    /// The class of a series, its scores, and how many of its readings lay outside the range
    /// the network was trained on ([`InputScale::outside`]): a class read from readings far
    /// outside it is an extrapolation, and says so. Errors as [`SoftnessNet::scores`].
    pub fn assess(&self, series: &[f32]) -> Result<Assessment, RunError> {
        Ok(assessment(&self.scale, series, self.scores(series)?))
    }
}

/// `series` (flat, [`N_VARIABLES`] readings per sample) as its samples.
///
/// Errors: [`RunError::Shape`] when it is empty or not whole samples (`expected` is then the
/// next whole length).
#[inline]
pub(crate) fn samples(series: &[f32]) -> Result<core::slice::ChunksExact<'_, f32>, RunError> {
    if series.is_empty() || !series.len().is_multiple_of(N_VARIABLES) {
        return Err(RunError::Shape {
            expected: series.len().div_ceil(N_VARIABLES).max(1) * N_VARIABLES,
            got: series.len(),
        });
    }
    Ok(series.chunks_exact(N_VARIABLES))
}

/// Sample `i`'s error as the series' error: a non-finite reading's index counts from the
/// series' start.
#[inline]
pub(crate) fn in_series(e: RunError, i: usize) -> RunError {
    match e {
        RunError::NonFinite { index } => RunError::NonFinite {
            index: i * N_VARIABLES + index,
        },
        other => other,
    }
}

/// The assessment of a series (whole samples) from its `scores` and the readings `scale`
/// finds outside the training range.
pub(crate) fn assessment(scale: &InputScale, series: &[f32], scores: [f32; CLASSES]) -> Assessment {
    let readings_outside = series
        .chunks_exact(N_VARIABLES)
        .map(|s| scale.outside(&core::array::from_fn(|j| s[j])))
        .sum();
    Assessment {
        class: class_of(&scores),
        scores,
        samples: series.len() / N_VARIABLES,
        readings_outside,
    }
}

/// The class of largest score (ties: the softer).
pub(crate) fn class_of(scores: &[f32; CLASSES]) -> Softness {
    let best = (1..CLASSES).fold(0, |b, k| if scores[k] > scores[b] { k } else { b });
    Softness::ALL[best]
}

/// A grasp's classification ([`SoftnessNet::assess`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Assessment {
    /// The class of largest mean score (ties: the softer).
    pub class: Softness,
    /// The mean outputs, [`Softness::ALL`] order.
    pub scores: [f32; CLASSES],
    /// Samples in the series.
    pub samples: usize,
    /// Readings (of `samples × 8`) outside the training range widened by [`RANGE_MARGIN`].
    pub readings_outside: usize,
}

/// The weights file's tensors: `net.{0,1,2}.{weight,bias}` in [`SoftnessNet::from_flat`]'s
/// order (weights row-major, outputs × inputs).
#[cfg(feature = "std")]
pub(crate) const TENSORS: [(&str, &[usize]); 6] = [
    ("net.0.weight", &[HIDDEN, N_VARIABLES]),
    ("net.0.bias", &[HIDDEN]),
    ("net.1.weight", &[HIDDEN, HIDDEN]),
    ("net.1.bias", &[HIDDEN]),
    ("net.2.weight", &[CLASSES, HIDDEN]),
    ("net.2.bias", &[CLASSES]),
];

#[cfg(feature = "std")]
impl SoftnessNet {
    /// Weights and scaling as a [`TensorFile`] (the tensors of [`SoftnessNet::from_file`],
    /// `input.min`, `input.gain`), `metadata` merged into the file's description.
    pub fn to_file(&self, metadata: serde_json::Value) -> Result<TensorFile, NetError> {
        let mut f = TensorFile::new();
        let flat = self.flat();
        let mut at = 0;
        for (name, shape) in TENSORS {
            let n: usize = shape.iter().product();
            f.insert(name, shape, &flat[at..at + n])?;
            at += n;
        }
        f.insert("input.min", &[N_VARIABLES], &self.scale.min)?;
        f.insert("input.gain", &[N_VARIABLES], &self.scale.gain)?;
        let mut meta = serde_json::json!({
            "model": "softness",
            "features": VARIABLE_NAMES,
            "hidden": [HIDDEN, HIDDEN],
            "classes": ["soft", "moderate", "hard"],
        });
        if let (Some(m), serde_json::Value::Object(extra)) = (meta.as_object_mut(), metadata) {
            m.extend(extra);
        }
        f.set_metadata(meta.to_string());
        Ok(f)
    }

    /// A classifier from [`SoftnessNet::to_file`]'s output.
    ///
    /// Errors: a tensor error for a missing or misshapen tensor, [`NetError::TensorMismatch`]
    /// for an input gain that is not finite.
    pub fn from_file(file: &TensorFile) -> Result<SoftnessNet, NetError> {
        let mut p = Vec::with_capacity(N_PARAMS);
        for (name, shape) in TENSORS {
            p.extend_from_slice(file.get(name, shape)?);
        }
        let arr = |name: &str| -> Result<[f32; N_VARIABLES], NetError> {
            let v = file.get(name, &[N_VARIABLES])?;
            Ok(core::array::from_fn(|j| v[j]))
        };
        let scale = InputScale {
            min: arr("input.min")?,
            gain: arr("input.gain")?,
        };
        SoftnessNet::from_flat(&p, scale).ok_or_else(|| NetError::TensorMismatch {
            name: "net".into(),
            stored: format!("{} parameters", p.len()),
            expected: format!("{N_PARAMS}"),
        })
    }

    /// Writes the classifier as a `.safetensors` file.
    pub fn save(&self, path: &Path, metadata: serde_json::Value) -> Result<(), NetError> {
        self.to_file(metadata)?.save(path)
    }

    /// Reads a classifier written by [`SoftnessNet::save`]; an error names the file.
    pub fn load(path: &Path) -> Result<SoftnessNet, NetError> {
        TensorFile::load_with(path, Self::from_file)
    }

    /// A classifier from the bytes of a weights file (one embedded with `include_bytes!`, or
    /// received); errors name it as `name`.
    pub fn from_bytes(name: &str, bytes: &[u8]) -> Result<SoftnessNet, NetError> {
        TensorFile::parse_with(name, bytes, Self::from_file)
    }
}

/// Input: a grasp's series, flat, [`N_VARIABLES`] readings per sample (see the module docs).
impl SoftnessClassifier for SoftnessNet {
    type Input = [f32];
    type Error = RunError;

    fn classify(&mut self, series: &[f32]) -> Result<Softness, RunError> {
        self.predict(series)
    }
}
