//! The contact MLP as a weights file holds it (feature `std`): plain arrays, no ML framework.

use super::{
    BASE_TERMS, DROPOUT, FEATURE_NAMES, HIDDEN, Head, N_FEATURES, Prediction, QuadraticBase,
    decode, in_range, standardised,
};
use crate::activations::sigmoid;
use crate::error::{NetError, check_output};
use crate::frozen::{Dense, Identity, Layer, Relu};
use crate::io::TensorFile;
use crate::stored::Stored;
use aot_locate::CELLS;
use hand_traits::{Contact, ContactLocator};
use std::path::Path;

/// The network with `O` outputs in plain arrays (what dfdx's trained stack freezes to: its
/// dropout is the identity at inference).
pub(super) type Fast<const O: usize> = (
    (Dense<N_FEATURES, 64>, Relu, Identity),
    (Dense<64, 32>, Relu, Identity),
    Dense<32, O>,
);

/// The network of each head; the centroid head's ensemble members (at least one).
#[derive(Debug, Clone, PartialEq)]
pub(super) enum Body {
    Area(Fast<1>),
    Cells(Fast<CELLS>),
    Centroid(Vec<Fast<2>>),
}

/// The most members a weights file may name (a bound on what a corrupt file makes us build).
pub(super) const MAX_MEMBERS: usize = 64;

/// Tensor-name prefix of ensemble member `i`: the first keeps a single network's names.
fn member_prefix(i: usize) -> String {
    if i == 0 {
        "net.".to_owned()
    } else {
        format!("member{i}.net.")
    }
}

/// Where `base` puts the centroid at the standardised inputs `z` (the origin without one):
/// what the network is trained to add to, and adds to at inference.
pub(super) fn base_at(base: Option<&QuadraticBase>, z: &[f32; N_FEATURES]) -> [f32; 2] {
    base.map_or([0.0; 2], |b| b.at(z))
}

/// A contact-area MLP from a weights file (or trained, with the `train` feature).
///
/// ```
/// use hand_traits::ContactLocator;
/// use tactile_nets::contact_mlp::ContactMlp;
/// use tactile_nets::pretrained;
///
/// // A weights file as `ContactMlp::save` (or `cargo xtask train contact-mlp`) writes it.
/// let path = std::env::temp_dir().join("contact-mlp-doc.safetensors");
/// pretrained::contact_mlp(1024)?.save(&path)?;
/// let mut mlp = ContactMlp::load(&path)?;
/// let features = [0.4, 0.9, 0.2, 0.27, 0.6, 0.13, 0.0, 2.0, 4.0];
/// assert_eq!(mlp.locate(&features)?.regions, 24);
/// assert!(mlp.locate(&[0.0; 3]).is_err()); // wrong shape: a typed error
/// # std::fs::remove_file(&path).ok();
/// # Ok::<(), tactile_nets::NetError>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct ContactMlp {
    pub(super) head: Head,
    pub(super) body: Body,
    /// The dropout rate it was trained with (recorded in the weights file).
    pub(super) dropout: f32,
    /// [`Head::Centroid`]'s quadratic base, when it was trained on one: the network's output
    /// is added to it.
    pub(super) base: Option<QuadraticBase>,
    pub(super) mean: [f32; N_FEATURES],
    pub(super) scale: [f32; N_FEATURES],
    pub(super) catalogue: Vec<u32>,
}

impl ContactMlp {
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
        let (out, n, _) = self.raw_outputs(input)?;
        Ok(out[..n].to_vec())
    }

    /// [`ContactMlp::outputs`] in a fixed buffer (the first `n` slots hold the head's outputs;
    /// localisation runs inside control cycles, where it must not allocate), and whether the
    /// input was [`in_range`].
    fn raw_outputs(&self, input: &[f32]) -> Result<([f32; CELLS], usize, bool), NetError> {
        let z = standardised(self.head, input, &self.mean, &self.scale)?;
        let mut out = [0.0f32; CELLS];
        let n = match &self.body {
            Body::Area(fast) => {
                out[..1].copy_from_slice(&fast.forward(z));
                1
            }
            Body::Cells(fast) => {
                out = fast.forward(z);
                CELLS
            }
            Body::Centroid(nets) => {
                let from = base_at(self.base.as_ref(), &z);
                let mut sum = [0.0f32; 2];
                for fast in nets {
                    let y = fast.forward(z);
                    sum = [sum[0] + y[0], sum[1] + y[1]];
                }
                let k = nets.len() as f32;
                out[..2].copy_from_slice(&[from[0] + sum[0] / k, from[1] + sum[1] / k]);
                2
            }
        };
        check_output(&out[..n])?;
        Ok((out, n, in_range(&z)))
    }

    /// Locates the contact for raw features (see [`ContactMlp::outputs`] for the errors),
    /// flagged out of range as [`super::StaticContactMlp`]'s predictions are.
    pub fn predict(&self, input: &[f32]) -> Result<Prediction, NetError> {
        let (out, n, in_range) = self.raw_outputs(input)?;
        Ok(Prediction {
            in_range,
            ..decode(&out[..n], self.catalogue.iter().copied())?
        })
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
            Body::Area(net) => net.write(&mut f, "net.")?,
            Body::Cells(net) => net.write(&mut f, "net.")?,
            Body::Centroid(members) => {
                for (i, net) in members.iter().enumerate() {
                    net.write(&mut f, &member_prefix(i))?;
                }
            }
        }
        // dfdx's dropout layers store their rate (a file trained with `train` has them).
        for prefix in (0..self.members()).map(member_prefix) {
            for layer in ["0.2", "1.2"] {
                f.insert(&format!("{prefix}{layer}.p"), &[], &[self.dropout])?;
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
        let body = match head {
            Head::AverageArea => Body::Area(Stored::read(file, "net.")?),
            Head::CellSet => Body::Cells(Stored::read(file, "net.")?),
            Head::Centroid => Body::Centroid(
                (0..members)
                    .map(|i| Stored::read(file, &member_prefix(i)))
                    .collect::<Result<_, _>>()?,
            ),
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

    /// A model from the bytes of a weights file (one embedded with `include_bytes!`, or
    /// received); errors name it as `name`.
    pub fn from_bytes(name: &str, bytes: &[u8]) -> Result<ContactMlp, NetError> {
        TensorFile::parse_with(name, bytes, Self::from_file)
    }
}

/// Input: the [`N_FEATURES`] raw features of [`features`](super::features); regions: the 24 cells, row-major.
impl ContactLocator for ContactMlp {
    type Input = [f32];
    type Error = NetError;

    fn locate(&mut self, input: &[f32]) -> Result<Contact, NetError> {
        Ok(self.predict(input)?.into())
    }
}
