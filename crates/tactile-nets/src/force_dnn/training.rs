//! Training the force DNN (feature `train`): the dfdx network, Adam, and dfdx's forward as the
//! reference the plain-array model is checked against.

use super::model::{Fast, NET};
use super::{ForceDnn, HIDDEN, N_INPUTS, OUTPUT_SPAN, WIDTHS, WeightSample, decoded, standardised};
use crate::error::NetError;
use crate::frozen::Freeze;
use crate::norm::{mean_and_scale, standardise};
use crate::train::{Loss, Samples, TrainConfig, TrainLog, fit};
use dfdx::prelude::*;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

type Arch<const H: usize> = (
    (Linear<N_INPUTS, H>, Sigmoid),
    (Linear<H, H>, ReLU),
    (Linear<H, H>, Sigmoid),
    (Linear<H, 1>, Sigmoid),
);
type Net<const H: usize> = <Arch<H> as BuildOnDevice<Cpu, f32>>::Built;

/// The dfdx network at one of the [`WIDTHS`].
enum Body {
    W4(Net<4>),
    W8(Net<8>),
    W16(Net<HIDDEN>),
    W32(Net<32>),
}

/// Runs `$e` with `$n` bound to the concrete network inside `$body`.
macro_rules! with_width {
    ($body:expr, $n:ident => $e:expr) => {
        match $body {
            Body::W4($n) => $e,
            Body::W8($n) => $e,
            Body::W16($n) => $e,
            Body::W32($n) => $e,
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

    fn freeze(&self) -> Result<Fast, NetError> {
        Ok(match self {
            Body::W4(n) => Fast::W4(n.freeze()?),
            Body::W8(n) => Fast::W8(n.freeze()?),
            Body::W16(n) => Fast::W16(n.freeze()?),
            Body::W32(n) => Fast::W32(n.freeze()?),
        })
    }
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
            let part = with_width!(&mut net, n => {
                fit::<_, N_INPUTS, 1>(&dev, n, &data, Loss::Mse, stage)?
            });
            log.epoch_loss.extend(part.epoch_loss);
        }
        let model = ForceDnn {
            fast: net.freeze()?,
            mean,
            scale,
            range_gf,
        };
        Ok((model, log))
    }

    /// [`ForceDnn::estimate_gf`] through dfdx's forward: the reference the plain-array
    /// network is checked against (it builds the dfdx network from the weights on every
    /// call, so it is slow).
    pub fn estimate_gf_dfdx(&self, rise_hpa: &[f32]) -> Result<f32, NetError> {
        let z = standardised(rise_hpa, &self.mean, &self.scale)?;
        let dev = Cpu::default();
        let mut net = Body::build(self.hidden(), &dev)?;
        let file = self.to_file()?;
        with_width!(&mut net, n => file.load_module(NET, n))?;
        let out = with_width!(&net, n => n.try_forward(dev.tensor(z))?.array()[0]);
        Ok(decoded(out, self.range_gf)?)
    }
}

/// The recipe for a recorded weight series (every frame of each settled weight, a few hundred
/// to a few thousand rows): minibatches of 64 frames, Adam 150 epochs at 3e-3, then 50 at 3e-4,
/// seeded `seed` and `seed + 1`. The built-in `sim` model was trained with it, and so is a
/// user's own fingertip (`handstack train force`).
pub fn series_recipe(seed: u64, progress: bool, label: &str) -> Vec<TrainConfig> {
    TrainConfig::stages(seed, progress, label, 64, &[(3e-3, 150), (3e-4, 50)])
}

/// The recipe for one user's weight session (a few hundred frames: ~20 weights of ~20 frames)
/// with [`mixup`]'s rows added (four times the rows): minibatches of 16 rows, Adam 150 epochs
/// at 3e-3, then 50 at 3e-4, seeded `seed` and `seed + 1` — as many Adam steps as 600 + 200
/// epochs of the frames alone. [`series_recipe`]'s minibatches of 64 are ~850 Adam steps on such
/// a session, too few: on one simulated fingertip of another skin (10 → 200 gf in 10 gf steps,
/// 1 s averages) its held-out weights came within 2.41 gf, this recipe's without mixup within
/// 1.51 … 2.83 gf over four seeds, with it within 1.26 … 1.70 gf; Table 1's recipe (10 000
/// full-batch epochs) fits the trained weights to 0.35 gf and misses a held-out one by 6.43 gf.
pub fn session_recipe(seed: u64, progress: bool, label: &str) -> Vec<TrainConfig> {
    TrainConfig::stages(seed, progress, label, 16, &[(3e-3, 150), (3e-4, 50)])
}

/// Rows mixed between neighbouring weights (mixup, Zhang et al. 2018, restricted to
/// neighbours): for each two consecutive entries of `steps` (sorted by weight, each a weight in
/// gf and its frames' rises), `per_frame` × the first's frame count rows `λ·a + (1−λ)·b` of a
/// frame `a` of the one and `b` of the other, weight `λ·wa + (1−λ)·wb`, λ uniform in [0, 1),
/// drawn from `seed`.
///
/// Why: a few tight clusters of frames (one per weight placed) let the network learn a
/// staircase — flat around each weight, steep between — which misreads every weight between
/// those it was trained on. The pad's response is smooth between neighbouring weights, and the
/// mixed rows say so (measured: [`session_recipe`]).
pub fn mixup(
    steps: &[(f32, &[[f32; N_INPUTS]])],
    per_frame: usize,
    seed: u64,
) -> Vec<WeightSample> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut out = Vec::new();
    for pair in steps.windows(2) {
        let [(wa, a), (wb, b)] = [pair[0], pair[1]];
        if a.is_empty() || b.is_empty() {
            continue;
        }
        for _ in 0..per_frame * a.len() {
            let l: f32 = rng.random();
            let (ra, rb) = (
                a[rng.random_range(0..a.len())],
                b[rng.random_range(0..b.len())],
            );
            out.push(WeightSample {
                rise_hpa: core::array::from_fn(|k| l * ra[k] + (1.0 - l) * rb[k]),
                weight_gf: l * wa + (1.0 - l) * wb,
            });
        }
    }
    out
}

/// `weight_gf` on the sigmoid's [`OUTPUT_SPAN`].
fn to_unit(weight_gf: f32, [lo, hi]: [f32; 2]) -> f32 {
    let [a, b] = OUTPUT_SPAN;
    a + (weight_gf - lo) / (hi - lo) * (b - a)
}
