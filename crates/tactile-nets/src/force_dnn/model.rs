//! The trainable force DNN (feature `std`): dfdx network, training, weights files.

use super::{HIDDEN, N_INPUTS, OUTPUT_SPAN, WIDTHS, WeightSample, decoded, standardised};
use crate::error::NetError;
use crate::frozen::{Freeze, Layer};
use crate::io::TensorFile;
use crate::norm::{mean_and_scale, standardise};
use crate::train::{Loss, Samples, TrainConfig, TrainLog, fit};
use dfdx::prelude::*;
use hand_traits::{ForceEstimate, ForceEstimator};
use std::path::Path;

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

    /// The weight, gf, for the three tared rises `rise_hpa` (hPa), through the frozen network.
    ///
    /// Errors: [`NetError::Shape`] unless `rise_hpa` has 3 values, [`NetError::NonFinite`] for
    /// a NaN or infinite value, [`NetError::NonFiniteOutput`] when a finite input overflows.
    pub fn estimate_gf(&self, rise_hpa: &[f32]) -> Result<f32, NetError> {
        let z = standardised(rise_hpa, &self.mean, &self.scale)?;
        Ok(decoded(
            with_width!(Fast, &self.fast, f => f.forward(z)[0]),
            self.range_gf,
        )?)
    }

    /// [`ForceDnn::estimate_gf`] through dfdx's forward (the reference the frozen copy is
    /// checked against; ~10 µs slower per call).
    pub fn estimate_gf_dfdx(&self, rise_hpa: &[f32]) -> Result<f32, NetError> {
        let z = standardised(rise_hpa, &self.mean, &self.scale)?;
        let out = with_width!(Body, &self.net, n => n.try_forward(self.dev.tensor(z))?.array()[0]);
        Ok(decoded(out, self.range_gf)?)
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

    /// Reads a model written by [`ForceDnn::save`]; an error names the file.
    pub fn load(path: &Path) -> Result<ForceDnn, NetError> {
        TensorFile::load_with(path, Self::from_file)
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

    /// The estimate, flagged out of range as [`super::StaticForceDnn`]'s is.
    fn estimate_force(&mut self, input: &[f32]) -> Result<ForceEstimate, NetError> {
        Ok(super::estimate(self.estimate_gf(input)?, self.range_gf()))
    }
}
