//! A seeded minibatch training loop for any dfdx model on `f32` rows, with an indicatif
//! progress bar.
//!
//! Determinism: the model is built on a `Cpu` seeded by the caller (initial weights and dropout
//! masks come from that device's generator), and minibatch order comes from a ChaCha8 stream
//! seeded by [`TrainConfig::seed`]. The same seed, data and machine give the same weights bit for
//! bit.

use crate::error::NetError;
use dfdx::optim::{Adam, AdamConfig, WeightDecay};
use dfdx::prelude::*;
use indicatif::{ProgressBar, ProgressStyle};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// How to train.
#[derive(Debug, Clone, PartialEq)]
pub struct TrainConfig {
    /// Passes over the training rows.
    pub epochs: usize,
    /// Rows per Adam step (the last batch of an epoch may be smaller).
    pub batch_size: usize,
    /// Adam learning rate.
    pub learning_rate: f64,
    /// L2 penalty added to every parameter's gradient (dfdx `WeightDecay::L2`); 0 for none.
    pub l2: f64,
    /// Seed of the minibatch order.
    pub seed: u64,
    /// Show an indicatif progress bar on stderr.
    pub progress: bool,
    /// Prefix of the progress bar.
    pub label: String,
}

impl TrainConfig {
    /// Training stages run one after the other, each `(learning rate, epochs)` of `plan` in
    /// minibatches of `batch_size`, seeded `seed`, `seed + 1`, …, labelled `label lr …`.
    ///
    /// ```
    /// use tactile_nets::train::TrainConfig;
    /// let s = TrainConfig::stages(8, false, "sim", 64, &[(3e-3, 150), (3e-4, 50)]);
    /// assert_eq!((s[1].seed, s[1].epochs, s[1].batch_size), (9, 50, 64));
    /// assert_eq!(s[0].label, "sim lr 3e-3");
    /// ```
    pub fn stages(
        seed: u64,
        progress: bool,
        label: &str,
        batch_size: usize,
        plan: &[(f64, usize)],
    ) -> Vec<TrainConfig> {
        plan.iter()
            .zip(seed..)
            .map(|(&(learning_rate, epochs), seed)| TrainConfig {
                epochs,
                batch_size,
                learning_rate,
                l2: 0.0,
                seed,
                progress,
                label: format!("{label} lr {learning_rate:e}"),
            })
            .collect()
    }
}

/// The loss between the model's last-layer outputs and the targets.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Loss {
    /// Mean squared error (regression).
    Mse,
    /// Softmax cross-entropy on logits; targets are probabilities (one-hot for classes).
    SoftmaxCrossEntropy,
    /// Independent sigmoid cross-entropy on logits; targets in `0..=1` (multi-label).
    SigmoidCrossEntropy,
}

/// Training rows: `inputs` holds `I` values per row, `targets` `O` per row.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Samples {
    /// Row-major inputs.
    pub inputs: Vec<f32>,
    /// Row-major targets.
    pub targets: Vec<f32>,
}

impl Samples {
    /// Appends one row.
    pub fn push(&mut self, input: &[f32], target: &[f32]) {
        self.inputs.extend_from_slice(input);
        self.targets.extend_from_slice(target);
    }
}

/// What training did: the mean loss of every epoch.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct TrainLog {
    /// Mean training loss per epoch (with dropout active).
    pub epoch_loss: Vec<f32>,
}

/// Trains `model` on `samples` with Adam (`betas` 0.9 / 0.999, `eps` 1e-8).
///
/// `dev` must be the device the model was built on: its generator draws the dropout masks.
pub fn fit<M, const I: usize, const O: usize>(
    dev: &Cpu,
    model: &mut M,
    samples: &Samples,
    loss: Loss,
    config: &TrainConfig,
) -> Result<TrainLog, NetError>
where
    M: TensorCollection<f32, Cpu>
        + ModuleMut<
            Tensor<(usize, Const<I>), f32, Cpu, OwnedTape<f32, Cpu>>,
            Output = Tensor<(usize, Const<O>), f32, Cpu, OwnedTape<f32, Cpu>>,
        >,
    <M as ModuleMut<Tensor<(usize, Const<I>), f32, Cpu, OwnedTape<f32, Cpu>>>>::Error:
        core::fmt::Debug,
{
    let rows = samples.inputs.len() / I.max(1);
    if I == 0 || O == 0 || rows == 0 {
        return Err(NetError::Training("no training rows".into()));
    }
    if samples.inputs.len() != rows * I || samples.targets.len() != rows * O {
        return Err(NetError::Training(format!(
            "{} input and {} target values do not make rows of {I} and {O}",
            samples.inputs.len(),
            samples.targets.len()
        )));
    }
    if config.batch_size == 0 {
        return Err(NetError::Training("batch size 0".into()));
    }
    if let Some(i) = samples
        .inputs
        .iter()
        .chain(&samples.targets)
        .position(|v| !v.is_finite())
    {
        return Err(NetError::NonFinite { index: i });
    }
    let weight_decay = (config.l2 > 0.0).then_some(WeightDecay::L2(config.l2));
    let mut opt = Adam::new(
        model,
        AdamConfig {
            lr: config.learning_rate,
            betas: [0.9, 0.999],
            eps: 1e-8,
            weight_decay,
        },
    );
    let mut grads = model.try_alloc_grads()?;
    let mut rng = ChaCha8Rng::seed_from_u64(config.seed);
    let mut order: Vec<usize> = (0..rows).collect();
    let bar = progress_bar(config);
    let mut log = TrainLog::default();
    let (mut x, mut y) = (Vec::new(), Vec::new());
    for _ in 0..config.epochs {
        shuffle(&mut order, &mut rng);
        let mut total = 0.0f32;
        for batch in order.chunks(config.batch_size) {
            x.clear();
            y.clear();
            for &r in batch {
                x.extend_from_slice(&samples.inputs[r * I..(r + 1) * I]);
                y.extend_from_slice(&samples.targets[r * O..(r + 1) * O]);
            }
            let b = batch.len();
            let xt = dev.tensor_from_vec(x.clone(), (b, Const::<I>));
            let yt = dev.tensor_from_vec(y.clone(), (b, Const::<O>));
            let out = model
                .try_forward_mut(xt.traced(grads))
                .map_err(|e| NetError::Device(format!("{e:?}")))?;
            let l = match loss {
                Loss::Mse => mse_loss(out, yt),
                Loss::SoftmaxCrossEntropy => cross_entropy_with_logits_loss(out, yt),
                Loss::SigmoidCrossEntropy => binary_cross_entropy_with_logits_loss(out, yt),
            };
            total += l.array() * b as f32;
            grads = l.try_backward()?;
            opt.update(model, &grads)
                .map_err(|e| NetError::Training(format!("{e:?}")))?;
            model.try_zero_grads(&mut grads)?;
        }
        let mean = total / rows as f32;
        if !mean.is_finite() {
            bar.abandon();
            return Err(NetError::Training(format!(
                "loss diverged at epoch {}",
                log.epoch_loss.len()
            )));
        }
        log.epoch_loss.push(mean);
        bar.set_message(format!("{mean:.4}"));
        bar.inc(1);
    }
    bar.finish();
    Ok(log)
}

/// Fisher–Yates with a seeded stream (`rand`'s own shuffle varies across its versions).
fn shuffle(order: &mut [usize], rng: &mut ChaCha8Rng) {
    for i in (1..order.len()).rev() {
        order.swap(i, rng.random_range(0..=i));
    }
}

fn progress_bar(config: &TrainConfig) -> ProgressBar {
    if !config.progress {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::new(config.epochs as u64);
    if let Ok(style) =
        ProgressStyle::with_template("{prefix:>24} [{bar:30}] {pos}/{len} epochs, loss {msg}")
    {
        bar.set_style(style.progress_chars("=> "));
    }
    bar.set_prefix(config.label.clone());
    bar
}
