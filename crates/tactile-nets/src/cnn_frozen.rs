//! The contact CNN's inference on plain arrays: the same arithmetic as the dfdx graph
//! (valid 3 × 3 conv, ReLU, 2 × 2 max-pool, dense + ReLU, dense), without dfdx's per-call
//! tensor allocations — the single-sample path the 50 µs budget is measured on.
//!
//! The conv kernel and the dense head are [`crate::frozen`] layers frozen from the trained
//! dfdx modules; this module adds only the patch walk and the pool. The tests check it
//! against dfdx's forward to 1e-5.

use crate::cnn_layers::{CONV_ROWS, KERNEL, PATCH, POOLED};
use crate::contact_cnn::{REGIONS, WINDOW, WINDOW_VALUES};
use crate::error::NetError;
use crate::frozen::{Dense, Freeze, Layer, Relu};
use dfdx::nn::modules::Linear;
use dfdx::prelude::{Cpu, ReLU};

/// The dense head `(Linear<FLAT, H>, ReLU, Linear<H, 9>)` as dfdx builds it.
pub type Head<const FLAT: usize, const H: usize> = (
    Linear<FLAT, H, f32, Cpu>,
    ReLU,
    Linear<H, REGIONS, f32, Cpu>,
);

/// A contact CNN with `F` filters, `FLAT = 18 · F` pooled features and a dense width `H`, as
/// plain arrays.
#[derive(Debug, Clone, PartialEq)]
pub struct FrozenCnn<const F: usize, const FLAT: usize, const H: usize> {
    conv: Dense<PATCH, F>,
    head: (Dense<FLAT, H>, Relu, Dense<H, REGIONS>),
}

impl<const F: usize, const FLAT: usize, const H: usize> FrozenCnn<F, FLAT, H> {
    const SIZES_AGREE: () = assert!(FLAT == POOLED * F, "FrozenCnn: FLAT must be 18 · F");

    /// Freezes a trained net's conv kernel (`Linear<9, F>`) and dense head.
    pub fn new(conv: &Linear<PATCH, F, f32, Cpu>, head: &Head<FLAT, H>) -> Result<Self, NetError> {
        let () = Self::SIZES_AGREE;
        Ok(FrozenCnn {
            conv: conv.freeze()?,
            head: head.freeze()?,
        })
    }

    /// Logits of a standardised window (channel-major 4 × 38).
    pub fn logits(&self, z: &[f32; WINDOW_VALUES]) -> [f32; REGIONS] {
        // Pooled map, `[column][filter]` as dfdx flattens it. ReLU commutes with max, so the
        // pool takes the max of the raw conv values and ReLU follows.
        let mut pooled = [f32::NEG_INFINITY; FLAT];
        for r in 0..CONV_ROWS {
            for c in 0..2 * POOLED {
                let patch: [f32; PATCH] =
                    core::array::from_fn(|k| z[(r + k / KERNEL) * WINDOW + c + k % KERNEL]);
                let y = self.conv.forward(patch);
                for (m, v) in pooled[(c / 2) * F..(c / 2 + 1) * F].iter_mut().zip(y) {
                    *m = m.max(v);
                }
            }
        }
        self.head.forward(Relu.forward(pooled))
    }
}
