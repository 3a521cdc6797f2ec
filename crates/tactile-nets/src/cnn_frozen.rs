//! The contact CNN's inference on plain arrays: the same arithmetic as the dfdx graph
//! (valid 3 × 3 conv, ReLU, 2 × 2 max-pool, dense + ReLU, dense), without dfdx's per-call
//! tensor allocations — the single-sample path the 50 µs budget is measured on.
//!
//! The conv kernel is copied patch-element-major and computed four columns at a time; the
//! dense head reads ReLU outputs, so both its layers are [`crate::frozen::SparseDense`]
//! (input-major, zeros skipped). The tests check it against dfdx's forward to 1e-5.

use crate::cnn_layers::{CONV_COLS, CONV_ROWS, KERNEL, PATCH, POOLED};

/// Conv columns computed together (it divides the 36 columns).
const GROUP: usize = 4;
const _: () = assert!(CONV_COLS.is_multiple_of(GROUP));
use crate::contact_cnn::{REGIONS, WINDOW, WINDOW_VALUES};
use crate::error::NetError;
use crate::frozen::{Freeze, SparseDense};
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
    // The 3 × 3 kernels patch-element-major: `conv[k][f]` is filter f's weight on element k.
    conv: Box<[[f32; F]; PATCH]>,
    conv_bias: [f32; F],
    // Both dense layers read ReLU outputs (the pooled map, the hidden layer): input-major, so
    // the zeros cost nothing.
    head: (SparseDense<FLAT, H>, SparseDense<H, REGIONS>),
}

impl<const F: usize, const FLAT: usize, const H: usize> FrozenCnn<F, FLAT, H> {
    const SIZES_AGREE: () = assert!(FLAT == POOLED * F, "FrozenCnn: FLAT must be 18 · F");

    /// Freezes a trained net's conv kernel (`Linear<9, F>`) and dense head.
    pub fn new(conv: &Linear<PATCH, F, f32, Cpu>, head: &Head<FLAT, H>) -> Result<Self, NetError> {
        let () = Self::SIZES_AGREE;
        let w = conv.weight.as_vec();
        let b = conv.bias.as_vec();
        if w.len() != F * PATCH || b.len() != F {
            return Err(NetError::TensorMismatch {
                name: "conv".to_owned(),
                stored: format!("{} weights, {} biases", w.len(), b.len()),
                expected: format!("[{F}, {PATCH}] and [{F}]"),
            });
        }
        let (dense, _, out) = head.freeze()?;
        Ok(FrozenCnn {
            conv: Box::new(core::array::from_fn(|k| {
                core::array::from_fn(|f| w[f * PATCH + k])
            })),
            conv_bias: core::array::from_fn(|f| b[f]),
            head: (
                SparseDense::from_dense(&dense),
                SparseDense::from_dense(&out),
            ),
        })
    }

    /// Logits of a standardised window (channel-major 4 × 38).
    pub fn logits(&self, z: &[f32; WINDOW_VALUES]) -> [f32; REGIONS] {
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx") {
            // SAFETY: the one requirement of a `target_feature` function is that the CPU has
            // the feature, checked just above. Why: the 8 filters of a conv column fill one
            // 8-lane register instead of two SSE2 ones (same lane-wise mul and add, same bits).
            #[allow(unsafe_code)]
            let pooled = unsafe { pool_avx::<F, FLAT>(&self.conv, &self.conv_bias, z) };
            return self.head(&pooled);
        }
        let pooled = pool::<F, FLAT>(&self.conv, &self.conv_bias, z);
        self.head(&pooled)
    }

    /// The dense head on the pooled map before its ReLU: each layer applies the ReLU before
    /// it as it skips the zeros.
    fn head(&self, pooled: &[f32; FLAT]) -> [f32; REGIONS] {
        let (hidden, out) = &self.head;
        out.forward_relu(&hidden.forward_relu(pooled))
    }
}

/// The max-pooled conv map of a window, `[column][filter]` as dfdx flattens it, before ReLU.
#[inline(always)]
fn pool<const F: usize, const FLAT: usize>(
    conv: &[[f32; F]; PATCH],
    conv_bias: &[f32; F],
    z: &[f32; WINDOW_VALUES],
) -> [f32; FLAT] {
    // Pooled map, `[column][filter]` as dfdx flattens it. ReLU commutes with max, so the
    // pool takes the max of the raw conv values and ReLU follows.
    let mut pooled = [f32::NEG_INFINITY; FLAT];
    for r in 0..CONV_ROWS {
        // Four neighbouring columns at once: four independent sums per filter, so the adds
        // of one column do not wait on each other (one column alone is latency-bound).
        for c0 in (0..CONV_COLS).step_by(GROUP) {
            let mut y = [*conv_bias; GROUP];
            for (k, w) in conv.iter().enumerate() {
                let at = (r + k / KERNEL) * WINDOW + c0 + k % KERNEL;
                for (y, &v) in y.iter_mut().zip(&z[at..at + GROUP]) {
                    for (y, w) in y.iter_mut().zip(w) {
                        *y += v * w;
                    }
                }
            }
            for (dc, y) in y.iter().enumerate() {
                let c = c0 + dc;
                for (m, &v) in pooled[(c / 2) * F..(c / 2 + 1) * F].iter_mut().zip(y) {
                    *m = m.max(v);
                }
            }
        }
    }
    pooled
}

/// [`pool`] compiled for AVX (8-lane `f32`), chosen at run time.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx")]
fn pool_avx<const F: usize, const FLAT: usize>(
    conv: &[[f32; F]; PATCH],
    conv_bias: &[f32; F],
    z: &[f32; WINDOW_VALUES],
) -> [f32; FLAT] {
    pool::<F, FLAT>(conv, conv_bias, z)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    #[test]
    fn the_avx_conv_gives_the_portable_bits() {
        let mut rng = ChaCha8Rng::seed_from_u64(23);
        let conv: [[f32; 8]; PATCH] =
            core::array::from_fn(|_| core::array::from_fn(|_| rng.random_range(-1.0..1.0)));
        let bias: [f32; 8] = core::array::from_fn(|_| rng.random_range(-1.0..1.0));
        for _ in 0..20 {
            let z: [f32; WINDOW_VALUES] = core::array::from_fn(|_| rng.random_range(-3.0f32..3.0));
            let portable = pool::<8, { 8 * POOLED }>(&conv, &bias, &z);
            assert!(portable.iter().all(|v| v.is_finite()));
            #[cfg(target_arch = "x86_64")]
            if std::arch::is_x86_feature_detected!("avx") {
                // SAFETY: the CPU has AVX, checked just above.
                #[allow(unsafe_code)]
                let avx = unsafe { pool_avx::<8, { 8 * POOLED }>(&conv, &bias, &z) };
                assert_eq!(avx.map(f32::to_bits), portable.map(f32::to_bits));
            }
        }
    }
}
