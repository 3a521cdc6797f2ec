//! The contact CNN over `'static` weights: the built-in networks with no `std` and no
//! allocation, their weights in flash on a microcontroller ([`crate::pretrained`]'s
//! `CONTACT_CNN_*`). Same arithmetic as [`ContactCnn`](super::ContactCnn) on the same
//! weights up to the order of the dense layers' additions (it skips no zeros).

use super::kernel::pool;
use super::{CHANNELS, PATCH, Prediction, REGIONS, Variant, WINDOW_VALUES, standardise};
use crate::error::{RunError, check_output};
use crate::frozen::{Layer, Relu, StaticDense};
use hand_traits::{Contact, ContactLocator};

/// A contact CNN with `F` filters, `FLAT = 18 · F` pooled features and a dense width `H`, its
/// weights `'static`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StaticCnn<const F: usize, const FLAT: usize, const H: usize> {
    // The 3 × 3 kernels patch-element-major: `conv[k][f]` is filter f's weight on element k.
    conv: &'static [[f32; F]; PATCH],
    conv_bias: &'static [f32; F],
    hidden: StaticDense<FLAT, H>,
    out: StaticDense<H, REGIONS>,
}

impl<const F: usize, const FLAT: usize, const H: usize> StaticCnn<F, FLAT, H> {
    /// A network over its conv kernels (patch-element-major, [`transposed`] from a weights
    /// file's filter-major rows), conv biases and dense layers.
    pub const fn new(
        conv: &'static [[f32; F]; PATCH],
        conv_bias: &'static [f32; F],
        hidden: StaticDense<FLAT, H>,
        out: StaticDense<H, REGIONS>,
    ) -> Self {
        Self {
            conv,
            conv_bias,
            hidden,
            out,
        }
    }

    /// Logits of a standardised window (channel-major 4 × 38).
    pub fn logits(&self, z: &[f32; WINDOW_VALUES]) -> [f32; REGIONS] {
        let pooled = Relu.forward(pool::<F, FLAT>(self.conv, self.conv_bias, z));
        self.out.forward(Relu.forward(self.hidden.forward(pooled)))
    }
}

/// Filter-major conv kernels (`[filter][element]`, as a weights file stores them) in the
/// patch-element-major order [`StaticCnn`] reads, at compile time.
pub const fn transposed<const F: usize>(w: &[[f32; PATCH]; F]) -> [[f32; F]; PATCH] {
    let mut t = [[0.0; F]; PATCH];
    let mut k = 0;
    while k < PATCH {
        let mut f = 0;
        while f < F {
            t[k][f] = w[f][k];
            f += 1;
        }
        k += 1;
    }
    t
}

/// A built-in contact CNN: its [`StaticCnn`], the training set's per-channel standardisation
/// and where its training windows sat after a tap's trigger.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StaticContactCnn<const F: usize, const FLAT: usize, const H: usize> {
    variant: Variant,
    net: StaticCnn<F, FLAT, H>,
    mean: &'static [f32; CHANNELS],
    scale: &'static [f32; CHANNELS],
    trigger_offset: Option<u8>,
}

impl<const F: usize, const FLAT: usize, const H: usize> StaticContactCnn<F, FLAT, H> {
    /// A model from its network, input standardisation and trigger offset (frames from a
    /// tap's pressure trigger to the centre of its training windows).
    pub const fn new(
        variant: Variant,
        net: StaticCnn<F, FLAT, H>,
        mean: &'static [f32; CHANNELS],
        scale: &'static [f32; CHANNELS],
        trigger_offset: Option<u8>,
    ) -> Self {
        Self {
            variant,
            net,
            mean,
            scale,
            trigger_offset,
        }
    }

    /// Which network this is.
    pub fn variant(&self) -> Variant {
        self.variant
    }

    /// As [`ContactCnn::trigger_offset`](super::ContactCnn::trigger_offset).
    pub fn trigger_offset(&self) -> Option<usize> {
        self.trigger_offset.map(usize::from)
    }

    /// The 9 logits for a raw window (152 values, channel-major: acc x, acc y in mm/s², gyro
    /// x, gyro y in mrad/s).
    ///
    /// Errors: [`RunError::Shape`] unless `window` has 152 values, [`RunError::NonFinite`] for
    /// a NaN or infinite value, [`RunError::NonFiniteOutput`] when a finite input far outside
    /// the training range overflows the network.
    pub fn logits(&self, window: &[f32]) -> Result<[f32; REGIONS], RunError> {
        let (z, _) = standardise(window, self.mean, self.scale)?;
        let out = self.net.logits(&z);
        check_output(&out)?;
        Ok(out)
    }

    /// Locates a contact from a raw window (errors as [`StaticContactCnn::logits`]), flagged
    /// out of range beyond [`super::Z_RANGE`].
    pub fn predict(&self, window: &[f32]) -> Result<Prediction, RunError> {
        let (z, in_range) = standardise(window, self.mean, self.scale)?;
        let logits = self.net.logits(&z);
        Prediction::of(&logits, in_range)
    }
}

/// Input: one raw 4 × 38 window (152 values); regions: the 9 of §IV-A, `3 · row group +
/// column`.
impl<const F: usize, const FLAT: usize, const H: usize> ContactLocator
    for StaticContactCnn<F, FLAT, H>
{
    type Input = [f32];
    type Error = RunError;

    fn locate(&mut self, input: &[f32]) -> Result<Contact, RunError> {
        Ok(self.predict(input)?.into())
    }
}
