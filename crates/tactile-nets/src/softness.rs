//! The softness classifier of the underactuated-hand softness paper ("Distinguish the Textures
//! of Grasped Objects…"), §3.3: an 8 → 4 → 4 → 3 network (two hidden layers of 4
//! logistic-sigmoid neurons, a linear "purelin" output), in nalgebra, trained by
//! Levenberg–Marquardt ([`crate::softness_train`]).
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
//! # Ok::<(), tactile_nets::NetError>(())
//! ```

use crate::error::{NetError, check_input, check_output};
use crate::io::TensorFile;
use hand_traits::{Softness, SoftnessClassifier};
use nalgebra::{RealField, SMatrix, SVector};
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
/// Trainable parameters: `8·4 + 4 + 4·4 + 4 + 4·3 + 3`.
pub const N_PARAMS: usize =
    N_VARIABLES * HIDDEN + HIDDEN + HIDDEN * HIDDEN + HIDDEN + HIDDEN * CLASSES + CLASSES;
/// Normalised inputs are clipped to `±INPUT_CLIP`: the training range is `[-1, 1]`, so this
/// only bites 50 training ranges away, where every hidden sigmoid is saturated; it keeps the
/// outputs finite for any finite input.
pub const INPUT_CLIP: f32 = 100.0;

/// The network's weights: `W·h + b` per layer, `W` of shape (outputs × inputs).
#[derive(Debug, Clone, PartialEq)]
pub struct Layers<T: RealField + Copy> {
    /// Input → hidden 1.
    pub w1: SMatrix<T, HIDDEN, N_VARIABLES>,
    /// Hidden 1 bias.
    pub b1: SVector<T, HIDDEN>,
    /// Hidden 1 → hidden 2.
    pub w2: SMatrix<T, HIDDEN, HIDDEN>,
    /// Hidden 2 bias.
    pub b2: SVector<T, HIDDEN>,
    /// Hidden 2 → output.
    pub w3: SMatrix<T, CLASSES, HIDDEN>,
    /// Output bias.
    pub b3: SVector<T, CLASSES>,
}

/// The activations of one forward pass (kept for the Jacobian).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pass<T: RealField + Copy> {
    /// Hidden layer 1 (sigmoid).
    pub h1: SVector<T, HIDDEN>,
    /// Hidden layer 2 (sigmoid).
    pub h2: SVector<T, HIDDEN>,
    /// Outputs (linear).
    pub y: SVector<T, CLASSES>,
}

/// The logistic sigmoid `1 / (1 + e^-z)`: `e^-z` may overflow to `+∞`, which gives 0, so the
/// result stays in `[0, 1]` for every non-NaN `z`.
fn logistic<T: RealField + Copy>(z: T) -> T {
    T::one() / (T::one() + (-z).exp())
}

impl<T: RealField + Copy> Layers<T> {
    /// Weights from a flat parameter vector: `w1` row-major, `b1`, `w2` row-major, `b2`, `w3`
    /// row-major, `b3` (the order of [`Layers::flat`] and of the Jacobian's columns).
    pub fn from_flat(p: &[T]) -> Option<Layers<T>> {
        if p.len() != N_PARAMS {
            return None;
        }
        let mut k = 0;
        let mut take = |n: usize| {
            k += n;
            &p[k - n..k]
        };
        Some(Layers {
            w1: SMatrix::from_row_slice(take(HIDDEN * N_VARIABLES)),
            b1: SVector::from_column_slice(take(HIDDEN)),
            w2: SMatrix::from_row_slice(take(HIDDEN * HIDDEN)),
            b2: SVector::from_column_slice(take(HIDDEN)),
            w3: SMatrix::from_row_slice(take(CLASSES * HIDDEN)),
            b3: SVector::from_column_slice(take(CLASSES)),
        })
    }

    /// The flat parameter vector ([`Layers::from_flat`]'s order).
    pub fn flat(&self) -> Vec<T> {
        let mut out = Vec::with_capacity(N_PARAMS);
        out.extend(self.w1.transpose().iter());
        out.extend(self.b1.iter());
        out.extend(self.w2.transpose().iter());
        out.extend(self.b2.iter());
        out.extend(self.w3.transpose().iter());
        out.extend(self.b3.iter());
        out
    }

    /// Forward pass on a normalised input.
    pub fn forward(&self, z: &SVector<T, N_VARIABLES>) -> Pass<T> {
        let h1 = (self.w1 * z + self.b1).map(logistic);
        let h2 = (self.w2 * h1 + self.b2).map(logistic);
        let y = self.w3 * h2 + self.b3;
        Pass { h1, h2, y }
    }

    /// `∂y_k / ∂p` for every output `k` (rows) and parameter `p` (columns, flat order), by
    /// back-propagation through the sigmoid layers (`σ' = σ(1 − σ)`).
    pub fn jacobian(
        &self,
        z: &SVector<T, N_VARIABLES>,
        pass: &Pass<T>,
    ) -> SMatrix<T, CLASSES, N_PARAMS> {
        let one = T::one();
        let d1 = pass.h1.map(|h| h * (one - h));
        let d2 = pass.h2.map(|h| h * (one - h));
        let o_b1 = HIDDEN * N_VARIABLES;
        let o_w2 = o_b1 + HIDDEN;
        let o_b2 = o_w2 + HIDDEN * HIDDEN;
        let o_w3 = o_b2 + HIDDEN;
        let o_b3 = o_w3 + CLASSES * HIDDEN;
        let mut j = SMatrix::<T, CLASSES, N_PARAMS>::zeros();
        for k in 0..CLASSES {
            // δ at hidden 2 and hidden 1 for output k.
            let g2: SVector<T, HIDDEN> = SVector::from_fn(|i, _| self.w3[(k, i)] * d2[i]);
            let g1: SVector<T, HIDDEN> = (self.w2.transpose() * g2).component_mul(&d1);
            for i in 0..HIDDEN {
                j[(k, o_w3 + k * HIDDEN + i)] = pass.h2[i];
                j[(k, o_b2 + i)] = g2[i];
                j[(k, o_b1 + i)] = g1[i];
                for l in 0..HIDDEN {
                    j[(k, o_w2 + i * HIDDEN + l)] = g2[i] * pass.h1[l];
                }
                for l in 0..N_VARIABLES {
                    j[(k, i * N_VARIABLES + l)] = g1[i] * z[l];
                }
            }
            j[(k, o_b3 + k)] = one;
        }
        j
    }
}

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

    /// The normalised input of one raw sample (finite for finite input).
    pub fn apply(&self, x: &[f32; N_VARIABLES]) -> SVector<f32, N_VARIABLES> {
        SVector::from_fn(|j, _| {
            // (x − min) may overflow to ±∞ for huge x; the clip brings it back.
            (self.gain[j] * (x[j] - self.min[j]) - 1.0).clamp(-INPUT_CLIP, INPUT_CLIP)
        })
    }
}

/// A trained softness classifier: weights (f32) and input scaling.
#[derive(Debug, Clone, PartialEq)]
pub struct SoftnessNet {
    layers: Layers<f32>,
    scale: InputScale,
}

impl SoftnessNet {
    /// A classifier from its weights and input scaling.
    pub fn new(layers: Layers<f32>, scale: InputScale) -> SoftnessNet {
        SoftnessNet { layers, scale }
    }

    /// The weights.
    pub fn layers(&self) -> &Layers<f32> {
        &self.layers
    }

    /// The input scaling.
    pub fn scale(&self) -> &InputScale {
        &self.scale
    }

    /// The three linear outputs for one raw sample of [`N_VARIABLES`] readings.
    ///
    /// Errors: [`NetError::Shape`] unless `sample` has 8 values, [`NetError::NonFinite`] for a
    /// NaN or infinite reading.
    pub fn sample_outputs(&self, sample: &[f32]) -> Result<[f32; CLASSES], NetError> {
        check_input(sample, N_VARIABLES)?;
        let x: [f32; N_VARIABLES] = core::array::from_fn(|j| sample[j]);
        let y = self.layers.forward(&self.scale.apply(&x)).y;
        let out = [y[0], y[1], y[2]];
        check_output(&out)?;
        Ok(out)
    }

    /// Mean outputs over a series given flat, [`N_VARIABLES`] readings per sample.
    ///
    /// Errors: [`NetError::Shape`] when the series is empty or not whole samples (`expected`
    /// is then the next whole length), [`NetError::NonFinite`] at the first bad reading.
    pub fn scores(&self, series: &[f32]) -> Result<[f32; CLASSES], NetError> {
        if series.is_empty() || !series.len().is_multiple_of(N_VARIABLES) {
            return Err(NetError::Shape {
                expected: series.len().div_ceil(N_VARIABLES).max(1) * N_VARIABLES,
                got: series.len(),
            });
        }
        let mut sum = [0.0f64; CLASSES];
        for (i, sample) in series.chunks_exact(N_VARIABLES).enumerate() {
            let y = self.sample_outputs(sample).map_err(|e| match e {
                NetError::NonFinite { index } => NetError::NonFinite {
                    index: i * N_VARIABLES + index,
                },
                other => other,
            })?;
            for k in 0..CLASSES {
                sum[k] += f64::from(y[k]);
            }
        }
        let n = (series.len() / N_VARIABLES) as f64;
        Ok(core::array::from_fn(|k| (sum[k] / n) as f32))
    }

    /// The class of a series ([`SoftnessNet::scores`]'s largest mean; ties: the softer).
    pub fn predict(&self, series: &[f32]) -> Result<Softness, NetError> {
        let s = self.scores(series)?;
        let best = (1..CLASSES).fold(0, |b, k| if s[k] > s[b] { k } else { b });
        Softness::from_index(best).ok_or_else(|| NetError::Training("no class".into()))
    }

    /// Weights and scaling as a [`TensorFile`] (`net.{0,1,2}.{weight,bias}`, `input.min`,
    /// `input.gain`; weights row-major, outputs × inputs).
    pub fn to_file(&self, metadata: serde_json::Value) -> Result<TensorFile, NetError> {
        let l = &self.layers;
        let mut f = TensorFile::new();
        let rows = |m: &dyn Fn(usize, usize) -> f32, r: usize, c: usize| -> Vec<f32> {
            (0..r)
                .flat_map(|i| (0..c).map(move |j| (i, j)))
                .map(|(i, j)| m(i, j))
                .collect()
        };
        f.insert(
            "net.0.weight",
            &[HIDDEN, N_VARIABLES],
            &rows(&|i, j| l.w1[(i, j)], HIDDEN, N_VARIABLES),
        )?;
        f.insert("net.0.bias", &[HIDDEN], l.b1.as_slice())?;
        f.insert(
            "net.1.weight",
            &[HIDDEN, HIDDEN],
            &rows(&|i, j| l.w2[(i, j)], HIDDEN, HIDDEN),
        )?;
        f.insert("net.1.bias", &[HIDDEN], l.b2.as_slice())?;
        f.insert(
            "net.2.weight",
            &[CLASSES, HIDDEN],
            &rows(&|i, j| l.w3[(i, j)], CLASSES, HIDDEN),
        )?;
        f.insert("net.2.bias", &[CLASSES], l.b3.as_slice())?;
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
    pub fn from_file(file: &TensorFile) -> Result<SoftnessNet, NetError> {
        let mut p = Vec::with_capacity(N_PARAMS);
        for (name, shape) in [
            ("net.0.weight", &[HIDDEN, N_VARIABLES][..]),
            ("net.0.bias", &[HIDDEN]),
            ("net.1.weight", &[HIDDEN, HIDDEN]),
            ("net.1.bias", &[HIDDEN]),
            ("net.2.weight", &[CLASSES, HIDDEN]),
            ("net.2.bias", &[CLASSES]),
        ] {
            p.extend_from_slice(file.get(name, shape)?);
        }
        let layers = Layers::from_flat(&p).ok_or_else(|| NetError::TensorMismatch {
            name: "net".into(),
            stored: format!("{} parameters", p.len()),
            expected: format!("{N_PARAMS}"),
        })?;
        let arr = |name: &str| -> Result<[f32; N_VARIABLES], NetError> {
            let v = file.get(name, &[N_VARIABLES])?;
            Ok(core::array::from_fn(|j| v[j]))
        };
        Ok(SoftnessNet {
            layers,
            scale: InputScale {
                min: arr("input.min")?,
                gain: arr("input.gain")?,
            },
        })
    }

    /// Writes the classifier as a `.safetensors` file.
    pub fn save(&self, path: &Path, metadata: serde_json::Value) -> Result<(), NetError> {
        self.to_file(metadata)?.save(path)
    }

    /// Reads a classifier written by [`SoftnessNet::save`].
    pub fn load(path: &Path) -> Result<SoftnessNet, NetError> {
        TensorFile::load_with(path, Self::from_file)
    }
}

/// Input: a grasp's series, flat, [`N_VARIABLES`] readings per sample (see the module docs).
impl SoftnessClassifier for SoftnessNet {
    type Input = [f32];
    type Error = NetError;

    fn classify(&mut self, series: &[f32]) -> Result<Softness, NetError> {
        self.predict(series)
    }
}
