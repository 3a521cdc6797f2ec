//! The force / weight DNN of Kim et al. 2020, §2.2: three tared fingertip pressures → the
//! weight on the pad, in gram-force.
//!
//! # Network
//! The paper: "sigmoid is used as the activation function for the input and output layers,
//! and a rectified linear unit (ReLU) and sigmoid are used for the hidden layer", Adam, MSE
//! (eq. 1). Here: 3 inputs → [`HIDDEN`] sigmoid → [`HIDDEN`] ReLU → [`HIDDEN`] sigmoid → 1
//! sigmoid output. The inputs are the pressure rises above the sensors' unloaded reading
//! ([`tared_table`]), standardised with the training set's mean and spread; the
//! target weight is mapped linearly onto [`OUTPUT_SPAN`] of the sigmoid (the rated range's
//! lightest weight at 0.1, heaviest at 0.9, a choice made before training, not fitted), so
//! estimates saturate 12.5 % of the range beyond it instead of running away.
//!
//! # Inference
//! Plain arrays, no allocation, no ML framework: [`StaticForceDnn`] over the built-in
//! `'static` weights (no `std`), [`ForceDnn`] (feature `std`) over a weights file's;
//! training (feature `train`) freezes dfdx's network into a [`ForceDnn`], and
//! `ForceDnn::estimate_gf_dfdx` keeps dfdx's forward as the reference.
//!
//! ```
//! # #[cfg(feature = "train")] {
//! use hand_traits::ForceEstimator;
//! use tactile_nets::force_dnn::{ForceDnn, tared_table};
//! use tactile_nets::train::TrainConfig;
//!
//! // Three rows of Table 1 of Kim et al. 2020: weight (gf) and the three pressures (hPa).
//! let rows = [(0.0, [1191.25, 1199.02, 1018.04]), (100.0, [1191.96, 1199.55, 1018.67]),
//!             (200.0, [1192.47, 1200.06, 1019.18])];
//! let samples = tared_table(&rows)?; // rises above the 0 gf row
//! let config = TrainConfig { epochs: 1000, batch_size: 3, learning_rate: 1e-2, l2: 0.0,
//!                            seed: 1, progress: false, label: String::new() };
//! let (mut dnn, _) = ForceDnn::train(&samples, [0.0, 200.0], &[config])?;
//! let f = dnn.estimate_force(&samples[1].rise_hpa)?;
//! assert!((f.gram_force() - 100.0).abs() < 10.0, "{}", f.gram_force());
//! assert!(dnn.estimate_force(&[0.1, 0.2]).is_err()); // wrong shape: a typed error
//! # }
//! # Ok::<(), Box<dyn core::error::Error>>(())
//! ```

use crate::error::{RunError, check_output};
use crate::frozen::{self, Layer, Logistic, Relu, StaticDense};
use crate::norm::standardise;
use hand_traits::{ForceEstimate, ForceEstimator};

#[cfg(feature = "std")]
mod model;
#[cfg(feature = "std")]
mod table;
#[cfg(feature = "train")]
mod training;
#[cfg(feature = "std")]
pub use model::ForceDnn;
#[cfg(feature = "std")]
pub use table::tared_table;
#[cfg(feature = "train")]
pub use training::{mixup, series_recipe, session_recipe};

/// One training or test sample: tared pressure rises and the true weight.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WeightSample {
    /// Pressure rise of sensors 1–3 above the unloaded reading, hPa.
    pub rise_hpa: [f32; 3],
    /// The weight on the pad, gf.
    pub weight_gf: f32,
}

/// A live tare for the DNN's input: the mean of the first `frames` frames per sensor, then each
/// frame's rises over it in hPa.
///
/// ```
/// use hand_traits::PressureFrame;
/// use tactile_nets::force_dnn::LiveTare;
///
/// let mut tare = LiveTare::new(2);
/// let frame = |p: f32| PressureFrame { t_us: 0, pressure_pa: [p, p + 10.0, p - 10.0] };
/// assert_eq!(tare.rise_hpa(&frame(100_000.0)), None); // taring
/// assert_eq!(tare.rise_hpa(&frame(100_100.0)), None);
/// assert_eq!(tare.rise_hpa(&frame(100_250.0)), Some([2.0, 2.0, 2.0]));
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LiveTare {
    frames: u32,
    sum_pa: [f64; 3],
    n: u32,
}

impl LiveTare {
    /// A tare over the first `frames` frames (at least one).
    pub fn new(frames: u32) -> LiveTare {
        LiveTare {
            frames: frames.max(1),
            sum_pa: [0.0; 3],
            n: 0,
        }
    }

    /// Adds `frame` to the tare while taring (`None`); afterwards its rises, hPa.
    pub fn rise_hpa(&mut self, frame: &hand_traits::PressureFrame<3>) -> Option<[f32; 3]> {
        if self.n < self.frames {
            for (s, p) in self.sum_pa.iter_mut().zip(frame.pressure_pa) {
                *s += f64::from(p);
            }
            self.n += 1;
            return None;
        }
        let n = f64::from(self.n);
        Some(core::array::from_fn(|k| {
            ((f64::from(frame.pressure_pa[k]) - self.sum_pa[k] / n) / 100.0) as f32
        }))
    }
}

/// Inputs: the rises of sensors 1–3, hPa.
pub const N_INPUTS: usize = 3;
/// Width of each of the three hidden layers.
pub const HIDDEN: usize = 16;
/// The sigmoid output values the lightest and heaviest training weights map to.
pub const OUTPUT_SPAN: [f32; 2] = [0.1, 0.9];

/// Hidden widths a force DNN can be built with: the committed models use [`HIDDEN`]; the
/// others are the model-size knob of the trade report (`papers trade`).
pub const WIDTHS: [usize; 4] = [4, 8, HIDDEN, 32];

/// `rise_hpa` checked and standardised with the training `mean` and `scale`.
pub(crate) fn standardised(
    rise_hpa: &[f32],
    mean: &[f32; N_INPUTS],
    scale: &[f32; N_INPUTS],
) -> Result<[f32; N_INPUTS], RunError> {
    let z = standardise(&frozen::input(rise_hpa)?, mean, scale);
    // A finite input can still overflow the standardisation: report it as the overflow it is.
    check_output(&z)?;
    Ok(z)
}

/// How far past its rated range an estimate may read and still count as in range, as a share
/// of the range: 2.5 % (5 gf of 0–200 gf), above the built-in models' error at their own
/// training weights (Table 1 fit RMSE 0.092 gf, hand-sim's series 1.91 gf per frame), far
/// below what a press beyond the range reads (the sigmoid output saturates 12.5 % of the range
/// past its heaviest weight: 5–9 kgf on the Table 1 model read ~213 gf).
pub const RANGE_MARGIN: f32 = 0.025;

/// The weights an estimate of a model rated for `range_gf` counts as in range over: the range
/// widened by [`RANGE_MARGIN`] on each side.
pub fn valid_range_gf([lo, hi]: [f32; 2]) -> [f32; 2] {
    let m = RANGE_MARGIN * (hi - lo);
    [lo - m, hi + m]
}

/// `gf` as an estimate of a model rated for `range_gf`: flagged out of range beyond
/// [`valid_range_gf`].
pub(crate) fn estimate(gf: f32, range_gf: [f32; 2]) -> ForceEstimate {
    ForceEstimate::from_gram_force(gf).within_gf(valid_range_gf(range_gf))
}

/// The sigmoid output `unit` back in gram-force over the rated range `range_gf`.
pub(crate) fn decoded(unit: f32, [lo, hi]: [f32; 2]) -> Result<f32, RunError> {
    let [a, b] = OUTPUT_SPAN;
    let gf = lo + (unit - a) / (b - a) * (hi - lo);
    check_output(&[gf])?;
    Ok(gf)
}

/// The frozen network of width [`HIDDEN`] over `'static` weights.
pub type StaticNet = (
    (StaticDense<N_INPUTS, HIDDEN>, Logistic),
    (StaticDense<HIDDEN, HIDDEN>, Relu),
    (StaticDense<HIDDEN, HIDDEN>, Logistic),
    (StaticDense<HIDDEN, 1>, Logistic),
);

/// A force DNN whose weights are `'static` (the models built into the crate,
/// [`crate::pretrained`]): no allocation, no `std`, weights in flash on a microcontroller.
/// It estimates as [`ForceDnn`] does (feature `std`) with the same weights.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StaticForceDnn {
    net: StaticNet,
    mean: &'static [f32; N_INPUTS],
    scale: &'static [f32; N_INPUTS],
    range_gf: &'static [f32; 2],
}

impl StaticForceDnn {
    /// A model from its network, input standardisation and rated range (gf).
    pub const fn new(
        net: StaticNet,
        mean: &'static [f32; N_INPUTS],
        scale: &'static [f32; N_INPUTS],
        range_gf: &'static [f32; 2],
    ) -> Self {
        Self {
            net,
            mean,
            scale,
            range_gf,
        }
    }

    /// The rated range (lightest, heaviest weight), gf.
    pub fn range_gf(&self) -> [f32; 2] {
        *self.range_gf
    }

    /// The weight, gf, for the three tared rises `rise_hpa` (hPa).
    ///
    /// Errors: [`RunError::Shape`] unless `rise_hpa` has 3 values, [`RunError::NonFinite`]
    /// for a NaN or infinite value, [`RunError::NonFiniteOutput`] when a finite input
    /// overflows.
    pub fn estimate_gf(&self, rise_hpa: &[f32]) -> Result<f32, RunError> {
        let z = standardised(rise_hpa, self.mean, self.scale)?;
        decoded(self.net.forward(z)[0], *self.range_gf)
    }
}

/// Input: the three tared rises, hPa.
impl ForceEstimator for StaticForceDnn {
    type Input = [f32];
    type Error = RunError;

    /// The estimate, [`ForceEstimate::in_range`] only within [`valid_range_gf`] of the rated
    /// range: a press beyond it saturates the network, and the estimate says so.
    fn estimate_force(&mut self, input: &[f32]) -> Result<ForceEstimate, RunError> {
        Ok(estimate(self.estimate_gf(input)?, *self.range_gf))
    }
}
