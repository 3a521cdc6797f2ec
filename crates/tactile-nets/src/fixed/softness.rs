//! The softness classifier in fixed point: [`FixedSoftnessNet`], the integer form of
//! [`SoftnessNet`](softness::SoftnessNet) (same inputs, same scores and classes to the
//! quantisation's error, same errors), `no_std` and allocation-free; the built-in one is
//! [`pretrained::FIXED_SOFTNESS`](crate::pretrained::FIXED_SOFTNESS).

use super::{Block, QDenseArray, logistic_of, normalise};
use crate::error::{RunError, check_input, check_output};
use crate::frozen::Layer;
use crate::softness::{self, Assessment, CLASSES, HIDDEN, InputScale, N_VARIABLES, class_of};
#[cfg(feature = "std")]
use crate::{
    NetError,
    softness::{SoftnessNet, TENSORS},
};
use hand_traits::{Softness, SoftnessClassifier};

/// The softness net in fixed point (8 → 4 logistic → 4 logistic → 3 linear), its weights by
/// value (188 bytes with their exponents).
///
/// The two logistic layers read their accumulators straight into the table's Q12 input, not
/// through a 15-bit block: Levenberg–Marquardt leaves weights of tens, so one neuron's
/// pre-activation can be hundreds while another's, near 0, decides its output (through a
/// block, the worst per-sample output error on the tests' seeded samples was about twice as
/// large). A grasp's scores are the output layer at the mean of the second
/// layer's outputs over the series: the output layer is linear, so that is the mean of the
/// per-sample outputs (the float model's scores), summed exactly in integers.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FixedSoftnessNet {
    hidden1: QDenseArray<N_VARIABLES, HIDDEN>,
    hidden2: QDenseArray<HIDDEN, HIDDEN>,
    out: QDenseArray<HIDDEN, CLASSES>,
    scale: InputScale,
}

impl FixedSoftnessNet {
    /// A classifier from its quantised layers and the float model's input scaling.
    pub const fn new(
        hidden1: QDenseArray<N_VARIABLES, HIDDEN>,
        hidden2: QDenseArray<HIDDEN, HIDDEN>,
        out: QDenseArray<HIDDEN, CLASSES>,
        scale: InputScale,
    ) -> Self {
        Self {
            hidden1,
            hidden2,
            out,
            scale,
        }
    }

    /// `net` quantised at run time by the rule `build.rs` applies to the built-in net (the
    /// [module docs](crate::fixed)): `FixedSoftnessNet::quantise(&pretrained::SOFTNESS)` is
    /// [`pretrained::FIXED_SOFTNESS`](crate::pretrained::FIXED_SOFTNESS).
    ///
    /// Errors: [`NetError::NonFiniteWeight`] naming the weights file's tensor (`net.1.bias`…)
    /// for a NaN or infinite weight or bias.
    #[cfg(feature = "std")]
    pub fn quantise(net: &SoftnessNet) -> Result<Self, NetError> {
        let flat = net.flat();
        // Weight and bias of each layer, in the weights file's order.
        let mut at = 0;
        let [w1, b1, w2, b2, w3, b3] = TENSORS.map(|(name, shape)| {
            let n: usize = shape.iter().product();
            at += n;
            (name, &flat[at - n..at])
        });
        Ok(Self {
            hidden1: super::quantise_layer(w1, b1)?,
            hidden2: super::quantise_layer(w2, b2)?,
            out: super::quantise_layer(w3, b3)?,
            scale: *net.scale(),
        })
    }

    /// The input scaling (the float model's).
    pub fn scale(&self) -> &InputScale {
        &self.scale
    }

    /// One raw sample checked and normalised as the float model does it (in `f32`).
    fn normalised(&self, sample: &[f32]) -> Result<[f32; N_VARIABLES], RunError> {
        check_input(sample, N_VARIABLES)?;
        let z = self.scale.apply(&core::array::from_fn(|j| sample[j]));
        // A variable that never varied in training (gain 0) reads NaN for an input whose
        // distance from its minimum overflows: the overflow it is.
        check_output(&z)?;
        Ok(z)
    }

    /// The second hidden layer's outputs (Q15, exponent 15) for a normalised sample.
    fn hidden(&self, z: &[f32; N_VARIABLES]) -> Block<HIDDEN> {
        let (acc, exp) = self.hidden1.accumulate(&Block::from_f32(z));
        let (acc, exp) = self.hidden2.accumulate(&logistic_of(&acc, exp));
        logistic_of(&acc, exp)
    }

    /// The three linear outputs for one raw sample; errors as
    /// [`SoftnessNet::sample_outputs`](softness::SoftnessNet::sample_outputs).
    pub fn sample_outputs(&self, sample: &[f32]) -> Result<[f32; CLASSES], RunError> {
        let z = self.normalised(sample)?;
        let out = self.out.forward(self.hidden(&z)).to_f32();
        check_output(&out)?;
        Ok(out)
    }

    /// Mean outputs over a series given flat, [`N_VARIABLES`] readings per sample; errors as
    /// [`SoftnessNet::scores`](softness::SoftnessNet::scores).
    pub fn scores(&self, series: &[f32]) -> Result<[f32; CLASSES], RunError> {
        // Each output of the second layer is within [0, 2^15): the sums of 2^48 samples fit.
        let mut sum = [0u64; HIDDEN];
        let mut n = 0u64;
        for (i, sample) in softness::samples(series)?.enumerate() {
            let z = self
                .normalised(sample)
                .map_err(|e| softness::in_series(e, i))?;
            for (s, &v) in sum.iter_mut().zip(&self.hidden(&z).v) {
                *s += u64::from(v.unsigned_abs());
            }
            n += 1;
        }
        // The means with up to 16 bits below Q15 (fewer for a sum too long to shift), rounded.
        let up = (sum.iter().fold(0, |m, &s| m | s).leading_zeros() as i32 - 1).clamp(0, 16);
        let mean = sum.map(|s| (((s << up) + n / 2) / n) as i64);
        let out = self.out.forward(normalise(&mean, 15 + up)).to_f32();
        check_output(&out)?;
        Ok(out)
    }

    /// The class of a series ([`FixedSoftnessNet::scores`]'s largest mean; ties: the softer).
    pub fn predict(&self, series: &[f32]) -> Result<Softness, RunError> {
        Ok(class_of(&self.scores(series)?))
    }

    /// The class, the scores and the readings outside the training range, as
    /// [`SoftnessNet::assess`](softness::SoftnessNet::assess) gives them.
    pub fn assess(&self, series: &[f32]) -> Result<Assessment, RunError> {
        Ok(softness::assessment(
            &self.scale,
            series,
            self.scores(series)?,
        ))
    }
}

/// Input: a grasp's series, flat, [`N_VARIABLES`] readings per sample, as
/// [`SoftnessNet`](softness::SoftnessNet).
impl SoftnessClassifier for FixedSoftnessNet {
    type Input = [f32];
    type Error = RunError;

    fn classify(&mut self, series: &[f32]) -> Result<Softness, RunError> {
        self.predict(series)
    }
}
