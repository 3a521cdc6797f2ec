//! The force / weight DNN of seed 000 §2.2: three tared fingertip pressures → the weight on
//! the pad, in gram-force.
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
//! Runs through the [`crate::frozen`] copy of the network (plain arrays, no allocation);
//! [`ForceDnn::estimate_gf_dfdx`] keeps the dfdx forward for comparison.
//!
//! ```
//! use hand_traits::ForceEstimator;
//! use tactile_nets::force_dnn::{ForceDnn, tared_table};
//! use tactile_nets::train::TrainConfig;
//!
//! // Three rows of seed 000 Table 1: weight (gf) and the three pressures (hPa).
//! let rows = [(0.0, [1191.25, 1199.02, 1018.04]), (100.0, [1191.96, 1199.55, 1018.67]),
//!             (200.0, [1192.47, 1200.06, 1019.18])];
//! let samples = tared_table(&rows)?; // rises above the 0 gf row
//! let config = TrainConfig { epochs: 1000, batch_size: 3, learning_rate: 1e-2, l2: 0.0,
//!                            seed: 1, progress: false, label: String::new() };
//! let (mut dnn, _) = ForceDnn::train(&samples, [0.0, 200.0], &[config])?;
//! let f = dnn.estimate_force(&samples[1].rise_hpa)?;
//! assert!((f.gram_force() - 100.0).abs() < 10.0, "{}", f.gram_force());
//! assert!(dnn.estimate_force(&[0.1, 0.2]).is_err()); // wrong shape: a typed error
//! # Ok::<(), tactile_nets::NetError>(())
//! ```

use crate::error::{NetError, check_output};
use crate::frozen::{self, Freeze, Layer};
use crate::io::TensorFile;
use crate::norm::{mean_and_scale, standardise};
use crate::train::{Loss, Samples, TrainConfig, TrainLog, fit};
use dfdx::prelude::*;
use hand_traits::{ForceEstimate, ForceEstimator};
use std::path::Path;

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

/// Tares `(weight_gf, pressures_hpa)` rows against the row whose weight is 0 (Table 1's form).
///
/// Errors: [`NetError::Data`] when no row has weight 0 or a value is not finite.
pub fn tared_table(rows: &[(f64, [f64; 3])]) -> Result<Vec<WeightSample>, NetError> {
    let (_, tare) = rows
        .iter()
        .find(|(w, _)| *w == 0.0)
        .ok_or_else(|| NetError::Data {
            line: 0,
            reason: "no 0 gf row to tare against".into(),
        })?;
    rows.iter()
        .enumerate()
        .map(|(i, (w, p))| {
            let s = WeightSample {
                rise_hpa: core::array::from_fn(|k| (p[k] - tare[k]) as f32),
                weight_gf: *w as f32,
            };
            finite(&s, i + 1)
        })
        .collect()
}

fn finite(s: &WeightSample, line: usize) -> Result<WeightSample, NetError> {
    if s.rise_hpa
        .iter()
        .chain([&s.weight_gf])
        .all(|v| v.is_finite())
    {
        Ok(*s)
    } else {
        Err(NetError::Data {
            line,
            reason: "non-finite value".into(),
        })
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

type Arch<const H: usize> = (
    (Linear<N_INPUTS, H>, Sigmoid),
    (Linear<H, H>, ReLU),
    (Linear<H, H>, Sigmoid),
    (Linear<H, 1>, Sigmoid),
);
type Net<const H: usize> = <Arch<H> as BuildOnDevice<Cpu, f32>>::Built;
type Frozen<const H: usize> = <Net<H> as Freeze>::Frozen;

/// The dfdx network at one of the [`WIDTHS`].
enum Body {
    W4(Net<4>),
    W8(Net<8>),
    W16(Net<HIDDEN>),
    W32(Net<32>),
}

/// Its frozen (plain-array) form.
enum Fast {
    W4(Frozen<4>),
    W8(Frozen<8>),
    W16(Frozen<HIDDEN>),
    W32(Frozen<32>),
}

/// Runs `$e` with `$n` bound to the concrete network (or frozen network) inside `$body`.
macro_rules! with_width {
    ($kind:ident, $body:expr, $n:ident => $e:expr) => {
        match $body {
            $kind::W4($n) => $e,
            $kind::W8($n) => $e,
            $kind::W16($n) => $e,
            $kind::W32($n) => $e,
        }
    };
}

impl Body {
    /// A freshly initialised network of width `hidden` on `dev`.
    fn build(hidden: usize, dev: &Cpu) -> Result<Body, NetError> {
        Ok(match hidden {
            4 => Body::W4(dev.build_module::<Arch<4>, f32>()),
            8 => Body::W8(dev.build_module::<Arch<8>, f32>()),
            HIDDEN => Body::W16(dev.build_module::<Arch<HIDDEN>, f32>()),
            32 => Body::W32(dev.build_module::<Arch<32>, f32>()),
            _ => {
                return Err(NetError::Training(format!(
                    "hidden width {hidden} is not one of {WIDTHS:?}"
                )));
            }
        })
    }

    fn hidden(&self) -> usize {
        match self {
            Body::W4(_) => 4,
            Body::W8(_) => 8,
            Body::W16(_) => HIDDEN,
            Body::W32(_) => 32,
        }
    }

    fn freeze(&self) -> Result<Fast, NetError> {
        Ok(match self {
            Body::W4(n) => Fast::W4(n.freeze()?),
            Body::W8(n) => Fast::W8(n.freeze()?),
            Body::W16(n) => Fast::W16(n.freeze()?),
            Body::W32(n) => Fast::W32(n.freeze()?),
        })
    }
}

/// A trained force / weight DNN.
pub struct ForceDnn {
    net: Body,
    fast: Fast,
    mean: [f32; N_INPUTS],
    scale: [f32; N_INPUTS],
    range_gf: [f32; 2],
    dev: Cpu,
}

impl ForceDnn {
    /// Trains on `samples` for the rated range `range_gf` (lightest, heaviest), running
    /// `stages` one after the other (each a fresh Adam with its own learning rate and epochs;
    /// the network is built on a device seeded by the first stage's seed).
    ///
    /// Errors: [`NetError::Training`] for no samples or stages, or a range that is empty or
    /// not finite; [`NetError::NonFinite`] for a non-finite sample.
    pub fn train(
        samples: &[WeightSample],
        range_gf: [f32; 2],
        stages: &[TrainConfig],
    ) -> Result<(ForceDnn, TrainLog), NetError> {
        Self::train_width(samples, range_gf, stages, HIDDEN)
    }

    /// [`ForceDnn::train`] with `hidden` units in each hidden layer (one of [`WIDTHS`]; the
    /// committed models use [`HIDDEN`]).
    ///
    /// Errors: as [`ForceDnn::train`], and [`NetError::Training`] for a width not in
    /// [`WIDTHS`].
    pub fn train_width(
        samples: &[WeightSample],
        range_gf: [f32; 2],
        stages: &[TrainConfig],
        hidden: usize,
    ) -> Result<(ForceDnn, TrainLog), NetError> {
        let first = stages
            .first()
            .ok_or_else(|| NetError::Training("no training stages".into()))?;
        if samples.is_empty() {
            return Err(NetError::Training("no weight samples".into()));
        }
        let rows: Vec<[f32; N_INPUTS]> = samples.iter().map(|s| s.rise_hpa).collect();
        let (mean, scale) = mean_and_scale(&rows);
        let [lo, hi] = range_gf;
        if !(hi > lo && lo.is_finite() && hi.is_finite()) {
            return Err(NetError::Training(format!(
                "rated range {lo}..{hi} gf is empty"
            )));
        }
        let mut data = Samples::default();
        for (row, s) in rows.iter().zip(samples) {
            data.push(
                &standardise(row, &mean, &scale),
                &[to_unit(s.weight_gf, range_gf)],
            );
        }
        let dev = Cpu::seed_from_u64(first.seed);
        let mut net = Body::build(hidden, &dev)?;
        let mut log = TrainLog::default();
        for stage in stages {
            let part = with_width!(Body, &mut net, n => {
                fit::<_, N_INPUTS, 1>(&dev, n, &data, Loss::Mse, stage)?
            });
            log.epoch_loss.extend(part.epoch_loss);
        }
        let fast = net.freeze()?;
        let model = ForceDnn {
            net,
            fast,
            mean,
            scale,
            range_gf,
            dev,
        };
        Ok((model, log))
    }

    /// Units in each hidden layer.
    pub fn hidden(&self) -> usize {
        self.net.hidden()
    }

    /// The rated range (lightest, heaviest weight), gf.
    pub fn range_gf(&self) -> [f32; 2] {
        self.range_gf
    }

    fn standardised(&self, rise_hpa: &[f32]) -> Result<[f32; N_INPUTS], NetError> {
        let z = standardise(&frozen::input(rise_hpa)?, &self.mean, &self.scale);
        // A finite input can still overflow the standardisation: report it as the overflow it is.
        check_output(&z)?;
        Ok(z)
    }

    fn decoded(&self, unit: f32) -> Result<f32, NetError> {
        let [lo, hi] = self.range_gf;
        let [a, b] = OUTPUT_SPAN;
        let gf = lo + (unit - a) / (b - a) * (hi - lo);
        check_output(&[gf])?;
        Ok(gf)
    }

    /// The weight, gf, for the three tared rises `rise_hpa` (hPa), through the frozen network.
    ///
    /// Errors: [`NetError::Shape`] unless `rise_hpa` has 3 values, [`NetError::NonFinite`] for
    /// a NaN or infinite value, [`NetError::NonFiniteOutput`] when a finite input overflows.
    pub fn estimate_gf(&self, rise_hpa: &[f32]) -> Result<f32, NetError> {
        let z = self.standardised(rise_hpa)?;
        self.decoded(with_width!(Fast, &self.fast, f => f.forward(z)[0]))
    }

    /// [`ForceDnn::estimate_gf`] through dfdx's forward (the reference the frozen copy is
    /// checked against; ~10 µs slower per call).
    pub fn estimate_gf_dfdx(&self, rise_hpa: &[f32]) -> Result<f32, NetError> {
        let z = self.standardised(rise_hpa)?;
        let out = with_width!(Body, &self.net, n => n.try_forward(self.dev.tensor(z))?.array()[0]);
        self.decoded(out)
    }

    /// Weights, input standardisation and output range as a [`TensorFile`].
    pub fn to_file(&self) -> Result<TensorFile, NetError> {
        let mut f = TensorFile::new();
        with_width!(Body, &self.net, n => f.add_module("net.", n)?);
        let h = self.hidden();
        f.insert("input.mean", &[N_INPUTS], &self.mean)?;
        f.insert("input.scale", &[N_INPUTS], &self.scale)?;
        f.insert("output.range_gf", &[2], &self.range_gf)?;
        let meta = serde_json::json!({
            "model": "force_dnn",
            "inputs": ["rise1_hpa", "rise2_hpa", "rise3_hpa"],
            "layers": [
                format!("linear 3->{h}, sigmoid"),
                format!("linear {h}->{h}, relu"),
                format!("linear {h}->{h}, sigmoid"),
                format!("linear {h}->1, sigmoid"),
            ],
            "output_span": OUTPUT_SPAN,
        });
        f.set_metadata(meta.to_string());
        Ok(f)
    }

    /// A model from [`ForceDnn::to_file`]'s output.
    pub fn from_file(file: &TensorFile) -> Result<ForceDnn, NetError> {
        let meta = file.metadata_json()?;
        if meta.get("model").and_then(|m| m.as_str()) != Some("force_dnn") {
            return Err(NetError::SafeTensors("metadata names no force DNN".into()));
        }
        let dev = Cpu::seed_from_u64(0);
        // The width is the one whose shapes the stored tensors fit (the committed width first).
        let mut found = Err(NetError::SafeTensors(
            "no force DNN width fits the tensors".into(),
        ));
        for hidden in [HIDDEN, 4, 8, 32] {
            let mut net = Body::build(hidden, &dev)?;
            match with_width!(Body, &mut net, n => file.load_module("net.", n)) {
                Ok(()) => {
                    found = Ok(net);
                    break;
                }
                Err(e) => found = Err(e),
            }
        }
        let net = found?;
        let vec3 = |name: &str| -> Result<[f32; N_INPUTS], NetError> {
            let v = file.get(name, &[N_INPUTS])?;
            Ok(core::array::from_fn(|j| v[j]))
        };
        let range = file.get("output.range_gf", &[2])?;
        Ok(ForceDnn {
            fast: net.freeze()?,
            net,
            mean: vec3("input.mean")?,
            scale: vec3("input.scale")?,
            range_gf: [range[0], range[1]],
            dev,
        })
    }

    /// Writes the model as a `.safetensors` file.
    pub fn save(&self, path: &Path) -> Result<(), NetError> {
        self.to_file()?.save(path)
    }

    /// Reads a model written by [`ForceDnn::save`].
    pub fn load(path: &Path) -> Result<ForceDnn, NetError> {
        Self::from_file(&TensorFile::load(path)?)
    }
}

/// `weight_gf` on the sigmoid's [`OUTPUT_SPAN`].
fn to_unit(weight_gf: f32, [lo, hi]: [f32; 2]) -> f32 {
    let [a, b] = OUTPUT_SPAN;
    a + (weight_gf - lo) / (hi - lo) * (b - a)
}

/// Input: the three tared rises, hPa ([`tared_table`]).
impl ForceEstimator for ForceDnn {
    type Input = [f32];
    type Error = NetError;

    fn estimate_force(&mut self, input: &[f32]) -> Result<ForceEstimate, NetError> {
        Ok(ForceEstimate::from_gram_force(self.estimate_gf(input)?))
    }
}
