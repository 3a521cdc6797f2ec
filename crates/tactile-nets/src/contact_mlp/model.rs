//! The trainable contact MLP (feature `std`): dfdx network, training, weights files.

use super::Options;
use super::{
    BASE_TERMS, ContactExample, DROPOUT, FEATURE_NAMES, HIDDEN, Head, N_FEATURES, Prediction,
    QuadraticBase, average_area, decode, features, head_inputs, standardised,
};
use crate::activations::sigmoid;
use crate::error::{NetError, check_output};
use crate::frozen::{Freeze, Layer};
use crate::io::TensorFile;
use crate::norm::{mean_and_scale, standardise};
use crate::train::{Loss, Samples, TrainConfig, TrainLog, fit};
use aot_locate::CELLS;
use dfdx::prelude::*;
use hand_traits::{Contact, ContactLocator};
use std::path::Path;

type Arch<const O: usize> = (
    (Linear<N_FEATURES, 64>, ReLU, Dropout),
    (Linear<64, 32>, ReLU, Dropout),
    Linear<32, O>,
);
type Net<const O: usize> = <Arch<O> as BuildOnDevice<Cpu, f32>>::Built;
/// The allocation-free inference copy of a [`Net`].
type Fast<const O: usize> = <Net<O> as Freeze>::Frozen;

/// The trained network (saved) and its frozen copy (run); the centroid head's ensemble
/// members (at least one) each as such a pair.
enum Body {
    Area(Net<1>, Fast<1>),
    Cells(Net<CELLS>, Fast<CELLS>),
    Centroid(Vec<(Net<2>, Fast<2>)>),
}

/// The most members a weights file may name (a bound on what a corrupt file makes us build).
const MAX_MEMBERS: usize = 64;

/// Tensor-name prefix of ensemble member `i`: the first keeps a single network's names.
fn member_prefix(i: usize) -> String {
    if i == 0 {
        "net.".to_owned()
    } else {
        format!("member{i}.net.")
    }
}

/// A trained contact-area MLP.
pub struct ContactMlp {
    head: Head,
    body: Body,
    /// The dropout rate it was trained with (recorded in the weights file).
    dropout: f32,
    /// [`Head::Centroid`]'s quadratic base, when it was trained on one: the network's output
    /// is added to it.
    base: Option<QuadraticBase>,
    mean: [f32; N_FEATURES],
    scale: [f32; N_FEATURES],
    catalogue: Vec<u32>,
}

/// The training-split contacts: distinct masks, smaller contacts first, then by mask.
fn catalogue_of(examples: &[ContactExample]) -> Vec<u32> {
    let mut masks: Vec<u32> = examples.iter().map(|e| e.mask).collect();
    masks.sort_by_key(|&m| (m.count_ones(), m));
    masks.dedup();
    masks
}

/// Where `base` puts the centroid at the standardised inputs `z` (the origin without one):
/// what the network is trained to add to, and adds to at inference.
fn base_at(base: Option<&QuadraticBase>, z: &[f32; N_FEATURES]) -> [f32; 2] {
    base.map_or([0.0; 2], |b| b.at(z))
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
                {
                    let fast = net.freeze()?;
                    (Body::Area(net, fast), log)
                }
            }
            Head::CellSet => {
                let mut net = build::<CELLS>(&dev, dropout);
                let loss = Loss::SigmoidCrossEntropy;
                let log = fit::<_, N_FEATURES, CELLS>(&dev, &mut net, &samples, loss, config)?;
                {
                    let fast = net.freeze()?;
                    (Body::Cells(net, fast), log)
                }
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
                    let fast = net.freeze()?;
                    nets.push((net, fast));
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

    /// The head this model was trained with.
    pub fn head(&self) -> Head {
        self.head
    }

    /// How many networks it averages: [`Head::Centroid`]'s ensemble size, 1 for the others.
    pub fn members(&self) -> usize {
        match &self.body {
            Body::Centroid(nets) => nets.len(),
            Body::Area(..) | Body::Cells(..) => 1,
        }
    }

    /// [`Head::Centroid`]'s quadratic base, if it was trained on one.
    pub fn quadratic_base(&self) -> Option<&QuadraticBase> {
        self.base.as_ref()
    }

    /// The contacts the decoder chooses from (cell masks).
    pub fn catalogue(&self) -> &[u32] {
        &self.catalogue
    }

    /// The network's raw outputs for raw features (the label value, the centroid's (row,
    /// column): the members' mean with the quadratic base added, or 24 cell logits).
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
        let z = standardised(self.head, input, &self.mean, &self.scale)?;
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
            Body::Centroid(nets) => {
                let from = base_at(self.base.as_ref(), &z);
                let mut sum = [0.0f32; 2];
                for (_, fast) in nets {
                    let y = fast.forward(z);
                    sum = [sum[0] + y[0], sum[1] + y[1]];
                }
                let k = nets.len() as f32;
                out[..2].copy_from_slice(&[from[0] + sum[0] / k, from[1] + sum[1] / k]);
                2
            }
        };
        check_output(&out[..n])?;
        Ok((out, n))
    }

    /// Locates the contact for raw features (see [`ContactMlp::outputs`] for the errors).
    pub fn predict(&self, input: &[f32]) -> Result<Prediction, NetError> {
        let (out, n) = self.raw_outputs(input)?;
        Ok(decode(&out[..n], self.catalogue.iter().copied())?)
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
            Body::Centroid(nets) => {
                for (i, (net, _)) in nets.iter().enumerate() {
                    f.add_module(&member_prefix(i), net)?;
                }
            }
        }
        if let Some(b) = &self.base {
            f.insert("base.quadratic", &[2, BASE_TERMS], b.coef.as_flattened())?;
        }
        f.insert("input.mean", &[N_FEATURES], &self.mean)?;
        f.insert("input.scale", &[N_FEATURES], &self.scale)?;
        // Masks are below 2^24, so f32 holds them exactly.
        let masks: Vec<f32> = self.catalogue.iter().map(|&m| m as f32).collect();
        f.insert("catalogue.masks", &[masks.len()], &masks)?;
        let mut meta = serde_json::json!({
            "model": "contact_mlp",
            "head": self.head.name(),
            "features": FEATURE_NAMES,
            "hidden": HIDDEN,
            "dropout": self.dropout,
        });
        // Named only when there is one: a file without a base keeps the bytes it had before
        // bases existed.
        if self.base.is_some() {
            meta["base"] = "quadratic".into();
        }
        if self.members() > 1 {
            meta["members"] = self.members().into();
        }
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
        let members = match meta.get("members") {
            None => 1,
            Some(m) => m
                .as_u64()
                .and_then(|m| usize::try_from(m).ok())
                .filter(|m| (1..=MAX_MEMBERS).contains(m))
                .ok_or_else(|| {
                    NetError::SafeTensors(format!("{m} ensemble members (1 to {MAX_MEMBERS})"))
                })?,
        };
        if members > 1 && head != Head::Centroid {
            return Err(NetError::SafeTensors(format!(
                "{members} ensemble members with the {} head",
                head.name()
            )));
        }
        let dev = Cpu::seed_from_u64(0);
        let body = match head {
            Head::AverageArea => {
                let mut net = build::<1>(&dev, DROPOUT);
                file.load_module("net.", &mut net)?;
                let fast = net.freeze()?;
                Body::Area(net, fast)
            }
            Head::CellSet => {
                let mut net = build::<CELLS>(&dev, DROPOUT);
                file.load_module("net.", &mut net)?;
                let fast = net.freeze()?;
                Body::Cells(net, fast)
            }
            Head::Centroid => {
                let mut nets = Vec::with_capacity(members);
                for i in 0..members {
                    let mut net = build::<2>(&dev, DROPOUT);
                    file.load_module(&member_prefix(i), &mut net)?;
                    let fast = net.freeze()?;
                    nets.push((net, fast));
                }
                Body::Centroid(nets)
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
        // Files written before the rate was configurable were all trained with the paper's.
        let dropout = meta
            .get("dropout")
            .and_then(|d| d.as_f64())
            .map_or(DROPOUT, |d| d as f32);
        let base = match file.tensor("base.quadratic") {
            None => None,
            Some(_) if head != Head::Centroid => {
                return Err(NetError::SafeTensors(format!(
                    "a quadratic base with the {} head",
                    head.name()
                )));
            }
            Some(_) => {
                let v = file.get("base.quadratic", &[2, BASE_TERMS])?;
                if v.iter().any(|c| !c.is_finite()) {
                    return Err(NetError::SafeTensors(
                        "a non-finite quadratic-base coefficient".into(),
                    ));
                }
                Some(QuadraticBase {
                    coef: core::array::from_fn(|o| core::array::from_fn(|j| v[o * BASE_TERMS + j])),
                })
            }
        };
        Ok(ContactMlp {
            head,
            body,
            dropout,
            base,
            mean: vec9("input.mean")?,
            scale: vec9("input.scale")?,
            catalogue,
        })
    }

    /// Writes the model as a `.safetensors` file.
    pub fn save(&self, path: &Path) -> Result<(), NetError> {
        self.to_file()?.save(path)
    }

    /// Reads a model written by [`ContactMlp::save`]; an error names the file.
    pub fn load(path: &Path) -> Result<ContactMlp, NetError> {
        TensorFile::load_with(path, Self::from_file)
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
