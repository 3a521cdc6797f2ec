//! The contact CNN in fixed point: [`FixedContactCnn`], quantised at run time from a
//! [`ContactCnn`] (whose weights come from a file), with its outputs (logits, region,
//! confidence) and errors.

use super::{Block, QDense, QDenseArray, normalise, quantise_layer, top_share};
use crate::cnn_frozen::Tensor;
use crate::contact_cnn::{
    self, CONV_COLS, CONV_ROWS, ContactCnn, KERNEL, PAPER, PATCH, POOLED, Prediction, REGIONS,
    SMALL, Variant, WIDE, WINDOW, WINDOW_VALUES,
};
use crate::error::{NetError, check_output};
use crate::frozen::{Layer, Relu};
use hand_traits::{Contact, ContactLocator};

/// A dense layer holding its weights in boxes (the paper net's hidden layer is 90 KiB).
type Boxed<const I: usize, const O: usize> = QDense<I, O, Box<[[i16; I]; O]>, Box<[i32; O]>>;

/// A contact CNN with `F` filters, `FLAT = 18 · F` pooled features and a dense width `H`, in
/// fixed point.
#[derive(Debug, Clone, PartialEq, Eq)]
struct Net<const F: usize, const FLAT: usize, const H: usize> {
    // The 3 × 3 kernels as a dense layer over a patch: a row per filter, patch row-major.
    conv: QDenseArray<PATCH, F>,
    hidden: Boxed<FLAT, H>,
    out: Boxed<H, REGIONS>,
}

impl<const F: usize, const FLAT: usize, const H: usize> Net<F, FLAT, H> {
    /// The network of [`ContactCnn::tensors`] (conv, hidden, output: weight then bias each).
    fn quantise(t: &[Tensor; 6]) -> Result<Self, NetError> {
        let part = |i: usize| (t[i].0.as_str(), t[i].2.as_slice());
        Ok(Net {
            conv: quantise_layer(part(0), part(1))?,
            hidden: quantise_layer(part(2), part(3))?,
            out: quantise_layer(part(4), part(5))?,
        })
    }

    /// The logits of a standardised window (one block).
    fn logits(&self, z: &Block<WINDOW_VALUES>) -> Block<REGIONS> {
        let hidden = Relu.forward(self.hidden.forward(self.pooled(z)));
        self.out.forward(hidden)
    }

    /// The conv map, 2 × 2 max-pooled and through its ReLU, `[column][filter]` as the float
    /// network flattens it.
    fn pooled(&self, z: &Block<WINDOW_VALUES>) -> Block<FLAT> {
        // Every patch shares the window's exponent, so every conv value comes out at the same
        // exponent and the pool compares the accumulators themselves.
        let mut pooled = [i64::MIN; FLAT];
        let mut exp = 0;
        for r in 0..CONV_ROWS {
            for c in 0..CONV_COLS {
                let patch = Block {
                    v: core::array::from_fn(|k| z.v[(r + k / KERNEL) * WINDOW + c + k % KERNEL]),
                    exp: z.exp,
                };
                let (y, at) = self.conv.accumulate(&patch);
                exp = at;
                for (m, y) in pooled[(c / 2) * F..(c / 2 + 1) * F].iter_mut().zip(y) {
                    *m = (*m).max(y);
                }
            }
        }
        // ReLU commutes with max: applied once, to the pool's survivors.
        normalise(&pooled.map(|v| v.max(0)), exp)
    }
}

/// The fixed-point network of each [`Variant`] (sizes as the float model's).
#[derive(Debug, Clone, PartialEq, Eq)]
enum Fast {
    Paper(Net<{ PAPER.0 }, { PAPER.0 * POOLED }, { PAPER.1 }>),
    Small(Net<{ SMALL.0 }, { SMALL.0 * POOLED }, { SMALL.1 }>),
    Wide(Net<{ WIDE.0 }, { WIDE.0 * POOLED }, { WIDE.1 }>),
}

/// A contact CNN in fixed point, quantised at run time from its float model (the float
/// model's weights come from a file): the convolution and both dense layers are integer
/// multiply-adds (`i16 × i16` into `i64`) over block-floating activations, the max-pool and
/// the ReLUs integer compares; the input's standardisation is the float model's, in `f32`.
///
/// It reads the float model's raw windows and answers with the same logits (to the
/// quantisation's error), region and confidence (the softmax share of the region, through
/// the `exp` table) and the same errors.
#[derive(Debug, Clone, PartialEq)]
pub struct FixedContactCnn {
    variant: Variant,
    mean: [f32; contact_cnn::CHANNELS],
    scale: [f32; contact_cnn::CHANNELS],
    trigger_offset: Option<usize>,
    net: Fast,
}

impl FixedContactCnn {
    /// `cnn` in fixed point, each of its six tensors quantised by the rule `build.rs` applies
    /// to the built-in models (the [module docs](crate::fixed), which also say what becomes of
    /// a tensor of zeros or of tiny values).
    ///
    /// Errors: [`NetError::NonFiniteWeight`] naming the tensor (`net.1.0.weight`…) for a NaN
    /// or infinite weight or bias (a weights file cannot hold one, a diverged training can).
    pub fn quantise(cnn: &ContactCnn) -> Result<FixedContactCnn, NetError> {
        let t = cnn.tensors();
        let net = match cnn.variant() {
            Variant::Paper => Fast::Paper(Net::quantise(&t)?),
            Variant::Small => Fast::Small(Net::quantise(&t)?),
            Variant::Wide => Fast::Wide(Net::quantise(&t)?),
        };
        let (mean, scale) = cnn.input_scale();
        Ok(FixedContactCnn {
            variant: cnn.variant(),
            mean,
            scale,
            trigger_offset: cnn.trigger_offset(),
            net,
        })
    }

    /// Which network this is.
    pub fn variant(&self) -> Variant {
        self.variant
    }

    /// The float model's [`ContactCnn::trigger_offset`].
    pub fn trigger_offset(&self) -> Option<usize> {
        self.trigger_offset
    }

    /// The logits as a block: the integer form's own output; and whether the window lay within
    /// [`contact_cnn::Z_RANGE`].
    fn block_logits(&self, window: &[f32]) -> Result<(Block<REGIONS>, bool), NetError> {
        let (z, in_range) = contact_cnn::standardise(window, &self.mean, &self.scale)?;
        let z = Block::from_f32(&z);
        let logits = match &self.net {
            Fast::Paper(n) => n.logits(&z),
            Fast::Small(n) => n.logits(&z),
            Fast::Wide(n) => n.logits(&z),
        };
        Ok((logits, in_range))
    }

    /// The 9 logits for a raw window; input and errors as [`ContactCnn::logits`].
    pub fn logits(&self, window: &[f32]) -> Result<[f32; REGIONS], NetError> {
        let out = self.block_logits(window)?.0.to_f32();
        check_output(&out)?;
        Ok(out)
    }

    /// Region of highest logit for each of many raw windows (the evaluation path).
    pub fn classify_batch(&self, windows: &[[f32; WINDOW_VALUES]]) -> Result<Vec<u8>, NetError> {
        windows
            .iter()
            .map(|w| self.logits(w).map(|l| contact_cnn::argmax(&l)))
            .collect()
    }

    /// Locates a contact from a raw window (errors as [`ContactCnn::logits`]): the region of
    /// highest logit (ties: the lower) and its softmax share, from the logits' integer gaps.
    pub fn predict(&self, window: &[f32]) -> Result<Prediction, NetError> {
        let (logits, in_range) = self.block_logits(window)?;
        check_output(&logits.to_f32())?;
        let region = contact_cnn::argmax(&logits.v.map(f32::from));
        let top = i32::from(logits.v[usize::from(region)]);
        let gaps = logits.v.iter().map(|&v| top - i32::from(v));
        Ok(Prediction {
            region,
            // The best's own gap, 0, always counts: the share is never missing.
            confidence: top_share(gaps, logits.exp).unwrap_or(1.0),
            in_range,
        })
    }
}

/// Input: one raw 4 × 38 window (152 values, as [`ContactCnn`]'s); regions: the 9 of §IV-A.
impl ContactLocator for FixedContactCnn {
    type Input = [f32];
    type Error = NetError;

    fn locate(&mut self, input: &[f32]) -> Result<Contact, NetError> {
        Ok(self.predict(input)?.into())
    }
}
