//! The contact CNN's inference on plain arrays: valid 3 × 3 conv, ReLU, 2 × 2 max-pool, a dense
//! layer with ReLU, a dense layer — the arithmetic of the dfdx graph it was trained as, without
//! dfdx and without an allocation per call.
//!
//! The conv kernel is copied patch-element-major and computed four columns at a time; the
//! dense head reads ReLU outputs, so both its layers are [`crate::frozen::SparseDense`]
//! (input-major, zeros skipped). The tests check it against dfdx's forward to 1e-5.

use crate::contact_cnn::kernel::pool;
use crate::contact_cnn::{PATCH, POOLED, REGIONS, WINDOW_VALUES};
use crate::error::NetError;
use crate::frozen::{Dense, SparseDense};
use crate::io::TensorFile;

/// The weights file's tensor names (dfdx's names for the training graph: the conv kernel is
/// layer 1 of block 0, the dense layers 0 and 2 of block 1).
const CONV: &str = "net.0.1";
const HIDDEN: &str = "net.1.0";
const OUT: &str = "net.1.2";

/// One stored tensor: its name, shape and row-major values.
pub(crate) type Tensor = (String, Vec<usize>, Vec<f32>);

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

    /// A network from its layers as a weights file stores them: the conv kernel row-major
    /// `F × 9` with `F` biases, the dense layers row-major (outputs × inputs).
    ///
    /// Errors: [`NetError::TensorMismatch`] when a length is wrong.
    pub fn from_rows(
        conv: &[f32],
        conv_bias: &[f32],
        hidden: &Dense<FLAT, H>,
        out: &Dense<H, REGIONS>,
    ) -> Result<Self, NetError> {
        let () = Self::SIZES_AGREE;
        if conv.len() != F * PATCH || conv_bias.len() != F {
            return Err(NetError::TensorMismatch {
                name: CONV.to_owned(),
                stored: format!("{} weights, {} biases", conv.len(), conv_bias.len()),
                expected: format!("[{F}, {PATCH}] and [{F}]"),
            });
        }
        Ok(FrozenCnn {
            conv: Box::new(core::array::from_fn(|k| {
                core::array::from_fn(|f| conv[f * PATCH + k])
            })),
            conv_bias: core::array::from_fn(|f| conv_bias[f]),
            head: (
                SparseDense::from_dense(hidden),
                SparseDense::from_dense(out),
            ),
        })
    }

    /// The network stored in `file` under dfdx's names (`net.0.1.weight`, …).
    ///
    /// Errors: [`NetError::MissingTensor`] / [`NetError::TensorMismatch`] for a tensor the
    /// file lacks or stores in another shape.
    pub fn from_file(file: &TensorFile) -> Result<Self, NetError> {
        let layer = |name: &str, o: usize, i: usize| -> Result<(&[f32], &[f32]), NetError> {
            Ok((
                file.get(&format!("{name}.weight"), &[o, i])?,
                file.get(&format!("{name}.bias"), &[o])?,
            ))
        };
        let (conv, conv_bias) = layer(CONV, F, PATCH)?;
        let (hw, hb) = layer(HIDDEN, H, FLAT)?;
        let (ow, ob) = layer(OUT, REGIONS, H)?;
        Self::from_rows(conv, conv_bias, &Dense::new(hw, hb)?, &Dense::new(ow, ob)?)
    }

    /// Adds the network's tensors to `file` under the names [`FrozenCnn::from_file`] reads.
    pub fn to_file(&self, file: &mut TensorFile) -> Result<(), NetError> {
        for (name, shape, values) in self.tensors() {
            file.insert(&name, &shape, &values)?;
        }
        Ok(())
    }

    /// The network's tensors as a weights file stores them: name, shape, row-major values —
    /// the conv kernel and bias, the hidden layer's weight and bias, the output layer's.
    pub(crate) fn tensors(&self) -> [Tensor; 6] {
        let conv: Vec<f32> = (0..F * PATCH)
            .map(|i| self.conv[i % PATCH][i / PATCH])
            .collect();
        let (hidden, out) = &self.head;
        [
            (format!("{CONV}.weight"), vec![F, PATCH], conv),
            (format!("{CONV}.bias"), vec![F], self.conv_bias.to_vec()),
            (
                format!("{HIDDEN}.weight"),
                vec![H, FLAT],
                hidden.weight_rows(),
            ),
            (format!("{HIDDEN}.bias"), vec![H], hidden.bias().to_vec()),
            (format!("{OUT}.weight"), vec![REGIONS, H], out.weight_rows()),
            (format!("{OUT}.bias"), vec![REGIONS], out.bias().to_vec()),
        ]
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

/// The conv and max-pool (`pool`) compiled for AVX (8-lane `f32`), chosen at run time.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx")]
fn pool_avx<const F: usize, const FLAT: usize>(
    conv: &[[f32; F]; PATCH],
    conv_bias: &[f32; F],
    z: &[f32; WINDOW_VALUES],
) -> [f32; FLAT] {
    pool::<F, FLAT>(conv, conv_bias, z)
}

#[cfg(all(test, feature = "train"))]
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
