//! Training the contact MLP (feature `train`): the dfdx network and Adam; the trained
//! networks are frozen into a [`ContactMlp`].

use super::Options;
use super::model::{Body, MAX_MEMBERS, base_at};
use super::{
    ContactExample, ContactMlp, DROPOUT, Head, N_FEATURES, QuadraticBase, average_area, features,
    head_inputs,
};
use crate::error::NetError;
use crate::frozen::Freeze;
use crate::norm::{mean_and_scale, standardise};
use crate::train::{Loss, Samples, TrainConfig, TrainLog, fit};
use aot_locate::CELLS;
use dfdx::prelude::*;

type Arch<const O: usize> = (
    (Linear<N_FEATURES, 64>, ReLU, Dropout),
    (Linear<64, 32>, ReLU, Dropout),
    Linear<32, O>,
);
type Net<const O: usize> = <Arch<O> as BuildOnDevice<Cpu, f32>>::Built;

/// The training-split contacts: distinct masks, smaller contacts first, then by mask.
fn catalogue_of(examples: &[ContactExample]) -> Vec<u32> {
    let mut masks: Vec<u32> = examples.iter().map(|e| e.mask).collect();
    masks.sort_by_key(|&m| (m.count_ones(), m));
    masks.dedup();
    masks
}

fn build<const O: usize>(dev: &Cpu, dropout: f32) -> Net<O> {
    let mut net = dev.build_module::<Arch<O>, f32>();
    net.0.2.p = dropout;
    net.1.2.p = dropout;
    net
}

impl ContactMlp {
    /// Trains a model with `head` on `examples` (the training split) using `config`'s epochs,
    /// batch size, learning rate and seeds (its `l2` is the paper's 0.001 unless changed).
    pub fn train(
        examples: &[ContactExample],
        head: Head,
        config: &TrainConfig,
    ) -> Result<(ContactMlp, TrainLog), NetError> {
        Self::train_with_dropout(examples, head, DROPOUT, config)
    }

    /// [`ContactMlp::train`] with another dropout rate than the paper's 30 % after each hidden
    /// layer (0 for none: a regression to fractions of a cell is blurred by dropout's noise).
    ///
    /// Errors: no examples, or a `dropout` outside `0.0..1.0`.
    pub fn train_with_dropout(
        examples: &[ContactExample],
        head: Head,
        dropout: f32,
        config: &TrainConfig,
    ) -> Result<(ContactMlp, TrainLog), NetError> {
        let options = Options {
            dropout,
            ..Options::default()
        };
        Self::train_with(examples, head, &options, config)
    }

    /// [`ContactMlp::train`] with `options`: the dropout rate, and for [`Head::Centroid`] a
    /// [`QuadraticBase`] fitted first on the same taps (the network learns what it leaves)
    /// and the ensemble's size. Member `i` is trained as a single network would be with
    /// `config.seed + i` (its initial weights and minibatch order), so member 0 is the model
    /// `options.members = 1` gives. The log holds the members' mean loss per epoch.
    ///
    /// ```
    /// use tactile_nets::contact_mlp::{ContactExample, ContactMlp, Head, Options, TapReading};
    /// use tactile_nets::train::TrainConfig;
    /// let tap = |left: f32, right: f32, centroid| ContactExample {
    ///     centroid,
    ///     ..ContactExample::new(
    ///         TapReading {
    ///             baseline_pa: [101_000.0; 3],
    ///             held_pa: [101_000.0 + left, 101_100.0, 101_000.0 + right],
    ///             arrival_ms: [Some(2.0); 3],
    ///         },
    ///         0,
    ///     )
    /// };
    /// let taps = [tap(3000.0, 500.0, [1.5, 1.5]), tap(500.0, 3000.0, [1.5, 5.5])];
    /// let options = Options { dropout: 0.0, quadratic_base: false, members: 3 };
    /// let config = TrainConfig {
    ///     epochs: 20, batch_size: 2, learning_rate: 1e-2, l2: 0.0, seed: 1,
    ///     progress: false, label: String::new(),
    /// };
    /// let (mlp, log) = ContactMlp::train_with(&taps, Head::Centroid, &options, &config)?;
    /// assert_eq!((mlp.members(), log.epoch_loss.len()), (3, 20));
    /// # Ok::<(), tactile_nets::NetError>(())
    /// ```
    ///
    /// Errors: as [`ContactMlp::train_with_dropout`]; a base or more than one member asked of
    /// another head than [`Head::Centroid`], no members, or a base whose fit fails.
    pub fn train_with(
        examples: &[ContactExample],
        head: Head,
        options: &Options,
        config: &TrainConfig,
    ) -> Result<(ContactMlp, TrainLog), NetError> {
        let Options {
            dropout,
            quadratic_base,
            members,
        } = *options;
        if (quadratic_base || members > 1) && head != Head::Centroid {
            return Err(NetError::Training(format!(
                "a quadratic base or an ensemble needs the centroid head, not {}",
                head.name()
            )));
        }
        if !(1..=MAX_MEMBERS).contains(&members) {
            return Err(NetError::Training(format!(
                "{members} ensemble members (1 to {MAX_MEMBERS})"
            )));
        }
        if !(0.0..1.0).contains(&dropout) {
            return Err(NetError::Training(format!(
                "dropout {dropout} is outside 0.0..1.0"
            )));
        }
        if examples.is_empty() {
            return Err(NetError::Training("no training taps".into()));
        }
        let rows: Vec<[f32; N_FEATURES]> = examples
            .iter()
            .map(|e| head_inputs(head, features(&e.reading)))
            .collect();
        let (mean, scale) = mean_and_scale(&rows);
        let z_rows: Vec<[f32; N_FEATURES]> =
            rows.iter().map(|r| standardise(r, &mean, &scale)).collect();
        let base = if quadratic_base {
            let targets: Vec<[f32; 2]> = examples.iter().map(|e| e.centroid).collect();
            Some(QuadraticBase::fit(&z_rows, &targets).ok_or_else(|| {
                NetError::Training("the quadratic base's least-squares fit failed".into())
            })?)
        } else {
            None
        };
        let mut samples = Samples::default();
        for (z, ex) in z_rows.iter().zip(examples) {
            let z = *z;
            match head {
                Head::AverageArea => samples.push(&z, &[average_area(ex.mask)]),
                Head::CellSet => {
                    let bits: [f32; CELLS] =
                        core::array::from_fn(|i| f32::from(u8::from(ex.mask & (1 << i) != 0)));
                    samples.push(&z, &bits);
                }
                Head::Centroid => {
                    let from = base_at(base.as_ref(), &z);
                    samples.push(&z, &[ex.centroid[0] - from[0], ex.centroid[1] - from[1]]);
                }
            }
        }
        let dev = Cpu::seed_from_u64(config.seed);
        let (body, log) = match head {
            Head::AverageArea => {
                let mut net = build::<1>(&dev, dropout);
                let log = fit::<_, N_FEATURES, 1>(&dev, &mut net, &samples, Loss::Mse, config)?;
                (Body::Area(net.freeze()?), log)
            }
            Head::CellSet => {
                let mut net = build::<CELLS>(&dev, dropout);
                let loss = Loss::SigmoidCrossEntropy;
                let log = fit::<_, N_FEATURES, CELLS>(&dev, &mut net, &samples, loss, config)?;
                (Body::Cells(net.freeze()?), log)
            }
            Head::Centroid => {
                let mut nets = Vec::with_capacity(members);
                // The members' mean loss per epoch: summed, then divided (exact for one).
                let mut log = TrainLog {
                    epoch_loss: vec![0.0; config.epochs],
                };
                for i in 0..members {
                    let config = TrainConfig {
                        seed: config.seed.wrapping_add(i as u64),
                        ..config.clone()
                    };
                    let dev = Cpu::seed_from_u64(config.seed);
                    let mut net = build::<2>(&dev, dropout);
                    let l = fit::<_, N_FEATURES, 2>(&dev, &mut net, &samples, Loss::Mse, &config)?;
                    for (sum, x) in log.epoch_loss.iter_mut().zip(l.epoch_loss) {
                        *sum += x;
                    }
                    nets.push(net.freeze()?);
                }
                for l in &mut log.epoch_loss {
                    *l /= members as f32;
                }
                (Body::Centroid(nets), log)
            }
        };
        let model = ContactMlp {
            head,
            body,
            dropout,
            base,
            mean,
            scale,
            catalogue: catalogue_of(examples),
        };
        Ok((model, log))
    }
}
