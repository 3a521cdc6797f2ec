//! The fingertip's models in fixed point: [`FixedForceDnn`] and [`FixedContactMlp`], the
//! integer forms of [`StaticForceDnn`](crate::force_dnn::StaticForceDnn) and
//! [`StaticContactMlp`](crate::contact_mlp::StaticContactMlp) (same inputs, same outputs,
//! same errors).

use super::{Block, QDense, top_share};
use crate::contact_mlp::{self, Head, N_FEATURES, Prediction};
use crate::error::{RunError, check_output};
use crate::force_dnn::{self, N_INPUTS};
use crate::frozen::{self, Identity, Layer, Logistic, Relu};
use aot_locate::CELLS;
use hand_traits::{Contact, ContactLocator, ForceEstimate, ForceEstimator};

/// The force DNN's layers in fixed point (3 → 16 sigmoid → 16 ReLU → 16 sigmoid → 1 sigmoid).
pub type FixedForceNet = (
    (QDense<N_INPUTS, { force_dnn::HIDDEN }>, Logistic),
    (QDense<{ force_dnn::HIDDEN }, { force_dnn::HIDDEN }>, Relu),
    (
        QDense<{ force_dnn::HIDDEN }, { force_dnn::HIDDEN }>,
        Logistic,
    ),
    (QDense<{ force_dnn::HIDDEN }, 1>, Logistic),
);

/// A force DNN in fixed point over `'static` weights: it estimates as its float model does, to
/// the quantisation's error (measured in `docs/trade.md`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FixedForceDnn {
    net: FixedForceNet,
    mean: &'static [f32; N_INPUTS],
    inv_scale: &'static [f32; N_INPUTS],
    range_gf: &'static [f32; 2],
}

impl FixedForceDnn {
    /// A model from its network, input standardisation (the training mean and the reciprocal
    /// of the training spread) and rated range (gf).
    pub const fn new(
        net: FixedForceNet,
        mean: &'static [f32; N_INPUTS],
        inv_scale: &'static [f32; N_INPUTS],
        range_gf: &'static [f32; 2],
    ) -> Self {
        Self {
            net,
            mean,
            inv_scale,
            range_gf,
        }
    }

    /// The rated range (lightest, heaviest weight), gf.
    pub fn range_gf(&self) -> [f32; 2] {
        *self.range_gf
    }

    /// The weight, gf, for the three tared rises `rise_hpa` (hPa); errors as
    /// [`StaticForceDnn::estimate_gf`](crate::force_dnn::StaticForceDnn::estimate_gf).
    pub fn estimate_gf(&self, rise_hpa: &[f32]) -> Result<f32, RunError> {
        let z = standardised(rise_hpa, self.mean, self.inv_scale)?;
        let out = self.net.forward(Block::from_f32(&z));
        force_dnn::decoded(out.to_f32()[0], *self.range_gf)
    }
}

/// Input: the three tared rises, hPa; flagged out of range as the float model's estimate is.
impl ForceEstimator for FixedForceDnn {
    type Input = [f32];
    type Error = RunError;

    fn estimate_force(&mut self, input: &[f32]) -> Result<ForceEstimate, RunError> {
        Ok(force_dnn::estimate(
            self.estimate_gf(input)?,
            *self.range_gf,
        ))
    }
}

/// `input` checked (its length, finite values) and standardised: `(x − mean) · inv_scale`.
fn standardised<const N: usize>(
    input: &[f32],
    mean: &[f32; N],
    inv_scale: &[f32; N],
) -> Result<[f32; N], RunError> {
    let x: [f32; N] = frozen::input(input)?;
    let z = core::array::from_fn(|j| (x[j] - mean[j]) * inv_scale[j]);
    // A finite input can still overflow: report it as the overflow it is.
    check_output(&z)?;
    Ok(z)
}

/// The cell-set contact MLP's layers in fixed point (9 → 64 ReLU → 32 ReLU → 24 logits).
pub type FixedMlpNet = (
    (QDense<N_FEATURES, 64>, Relu, Identity),
    (QDense<64, 32>, Relu, Identity),
    QDense<32, CELLS>,
);

/// A cell-set contact MLP in fixed point over `'static` weights and catalogue; the catalogue
/// decode in integers too (sums of logits, the posterior through
/// [`exp_neg_q16`](super::exp_neg_q16)).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FixedContactMlp {
    net: FixedMlpNet,
    mean: &'static [f32; N_FEATURES],
    inv_scale: &'static [f32; N_FEATURES],
    catalogue: &'static [u32],
}

impl FixedContactMlp {
    /// A model from its network, input standardisation (the training mean and the reciprocal
    /// of the training spread) and catalogue (cell masks).
    pub const fn new(
        net: FixedMlpNet,
        mean: &'static [f32; N_FEATURES],
        inv_scale: &'static [f32; N_FEATURES],
        catalogue: &'static [u32],
    ) -> Self {
        Self {
            net,
            mean,
            inv_scale,
            catalogue,
        }
    }

    /// The contacts the decoder chooses from (cell masks).
    pub fn catalogue(&self) -> impl Iterator<Item = u32> + '_ {
        self.catalogue.iter().copied()
    }

    /// Locates the contact for the raw features `input`; errors as
    /// [`StaticContactMlp::predict`](crate::contact_mlp::StaticContactMlp::predict).
    pub fn predict(&self, input: &[f32]) -> Result<Prediction, RunError> {
        let x = contact_mlp::head_inputs(Head::CellSet, frozen::input(input)?);
        let z = standardised(&x, self.mean, self.inv_scale)?;
        let logits = self.net.forward(Block::from_f32(&z));
        let (contact, confidence) =
            decode_cells(&logits, self.catalogue).ok_or(RunError::EmptyCatalogue)?;
        check_output(&[confidence])?;
        let centroid = contact_mlp::centroid_of(contact);
        Ok(Prediction {
            contact,
            region: contact_mlp::region_at(centroid),
            confidence,
            centroid,
            in_range: contact_mlp::in_range(&z),
        })
    }
}

/// The catalogue entry of highest likelihood under the cell logits and its posterior share,
/// as `contact_mlp`'s float decode computes them (an entry scores the sum of its cells'
/// logits; the posterior is `1 / Σ_j e^(ll_j − best)`), in integers: two passes, no buffer.
/// An entry with a cell past the logits can never be touched; when no entry can, the first
/// wins with an equal share (as the float decode's `−∞` scores give).
fn decode_cells(logits: &Block<CELLS>, catalogue: &[u32]) -> Option<(u32, f32)> {
    // Scores fit an `i32`: at most 24 cells of at most 32767.
    let score = |m: u32| -> Option<i32> {
        let mut bits = m;
        let mut ll = 0i32;
        while bits != 0 {
            let i = bits.trailing_zeros() as usize;
            bits &= bits - 1;
            ll += i32::from(*logits.v.get(i)?);
        }
        Some(ll)
    };
    let first = *catalogue.first()?;
    let mut best: Option<(u32, i32)> = None;
    for &m in catalogue {
        if let Some(ll) = score(m) {
            if best.is_none_or(|(_, b)| ll > b) {
                best = Some((m, ll));
            }
        }
    }
    let Some((contact, top)) = best else {
        return Some((first, 1.0 / catalogue.len() as f32));
    };
    let gaps = catalogue
        .iter()
        .filter_map(|&m| score(m))
        .map(|ll| top - ll);
    top_share(gaps, logits.exp).map(|share| (contact, share))
}

/// Input: the [`N_FEATURES`] raw features of [`contact_mlp::features`]; regions: the 24
/// cells, row-major.
impl ContactLocator for FixedContactMlp {
    type Input = [f32];
    type Error = RunError;

    fn locate(&mut self, input: &[f32]) -> Result<Contact, RunError> {
        Ok(self.predict(input)?.into())
    }
}
