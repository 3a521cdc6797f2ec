//! The two parameter-free layers that make a 3 × 3 convolution and a 2 × 2 max-pool out of
//! dfdx's stable ops (its `Conv2D` / `MaxPool2D` need the `nightly` feature): [`Im2Col`]
//! gathers each output position's 3 × 3 patch into a row, so the convolution is one
//! `Linear<9, F>` over all patches; [`PoolFlatten`] reshapes the conv map so each 2 × 2 pool
//! window lies on one axis and takes its max, then flattens.
//!
//! Geometry (the 4 × 38 image of Al & Martinez-Hernandez, §IV-A; MATLAB's default `Padding`
//! 0, i.e. a *valid* convolution): 3 × 3 conv → 2 × 36 map; 2 × 2 max-pool, stride 2 → 1 × 18
//! per filter.
//!
//! Patch rows are ordered `[sample][pool slot 0..4][pooled column 0..18]`, the pool slot being
//! (conv row `r`, column parity `dc`), so the four members of a pool window are
//! [`POOLED`] rows apart and one reshape puts them on an axis of their own.

use crate::contact_cnn::{CHANNELS, WINDOW, WINDOW_VALUES};
use dfdx::nn::modules::{Module, NonMutableModule, ZeroSizedModule};
use dfdx::prelude::*;

/// Kernel side.
pub const KERNEL: usize = 3;
/// Values per patch (3 × 3).
pub const PATCH: usize = KERNEL * KERNEL;
/// Rows of the conv map (valid convolution over 4 signals).
pub const CONV_ROWS: usize = CHANNELS - KERNEL + 1;
/// Columns of the conv map (valid convolution over 38 samples).
pub const CONV_COLS: usize = WINDOW - KERNEL + 1;
/// Members of a 2 × 2 pool window.
pub const POOL_SLOTS: usize = 4;
/// Columns after the 2 × 2, stride-2 max-pool (the single pooled row is 1 high).
pub const POOLED: usize = CONV_COLS / 2;
/// Conv positions per sample (2 × 36).
pub const POSITIONS: usize = POOL_SLOTS * POOLED;

// The pool consumes the whole conv map: 2 rows, an even number of columns.
const _: () = assert!(CONV_ROWS == 2 && CONV_COLS.is_multiple_of(2));

/// Index into a channel-major window of patch element `k` (row-major 3 × 3) of patch row `p`
/// (see the module docs for the row order).
pub fn patch_index(p: usize, k: usize) -> usize {
    let (slot, pooled) = (p / POOLED, p % POOLED);
    let (r, c) = (slot / 2, 2 * pooled + slot % 2);
    (r + k / KERNEL) * WINDOW + c + k % KERNEL
}

/// `(batch, 152)` windows → `(batch · 72, 9)` patches, differentiable (a dfdx `gather`).
#[derive(Debug, Default, Clone, Copy)]
pub struct Im2Col;

impl ZeroSizedModule for Im2Col {}
impl NonMutableModule for Im2Col {}

impl<T: Tape<f32, Cpu>> Module<Tensor<(usize, Const<WINDOW_VALUES>), f32, Cpu, T>> for Im2Col {
    type Output = Tensor<(usize, Const<PATCH>), f32, Cpu, T>;
    type Error = <Cpu as HasErr>::Err;

    fn try_forward(
        &self,
        x: Tensor<(usize, Const<WINDOW_VALUES>), f32, Cpu, T>,
    ) -> Result<Self::Output, Self::Error> {
        let b = x.shape().0;
        let one: Vec<usize> = (0..POSITIONS * PATCH)
            .map(|i| patch_index(i / PATCH, i % PATCH))
            .collect();
        let idx: Vec<usize> = (0..b).flat_map(|_| one.iter().copied()).collect();
        let idx = x
            .device()
            .try_tensor_from_vec(idx, (b, Const::<{ POSITIONS * PATCH }>))?;
        x.try_gather::<(usize, Const<{ POSITIONS * PATCH }>), _>(idx)?
            .try_reshape_like(&(b * POSITIONS, Const::<PATCH>))
    }
}

/// `(batch · 72, F)` conv outputs → 2 × 2 max-pool → `(batch, OUT)` with `OUT = 18 · F`,
/// flattened pooled-column-major (`[column][filter]`).
#[derive(Debug, Default, Clone, Copy)]
pub struct PoolFlatten<const F: usize, const OUT: usize>;

impl<const F: usize, const OUT: usize> PoolFlatten<F, OUT> {
    const SIZES_AGREE: () = assert!(OUT == POOLED * F, "PoolFlatten: OUT must be 18 · F");
}

impl<const F: usize, const OUT: usize> ZeroSizedModule for PoolFlatten<F, OUT> {}
impl<const F: usize, const OUT: usize> NonMutableModule for PoolFlatten<F, OUT> {}

impl<const F: usize, const OUT: usize, T: Tape<f32, Cpu>>
    Module<Tensor<(usize, Const<F>), f32, Cpu, T>> for PoolFlatten<F, OUT>
{
    type Output = Tensor<(usize, Const<OUT>), f32, Cpu, T>;
    type Error = <Cpu as HasErr>::Err;

    fn try_forward(
        &self,
        x: Tensor<(usize, Const<F>), f32, Cpu, T>,
    ) -> Result<Self::Output, Self::Error> {
        let () = Self::SIZES_AGREE;
        let b = x.shape().0 / POSITIONS;
        let windows = x.try_reshape_like(&(b, Const::<POOL_SLOTS>, Const::<POOLED>, Const::<F>))?;
        windows
            .try_max::<(usize, Const<POOLED>, Const<F>), Axis<1>>()?
            .try_reshape_like(&(b, Const::<OUT>))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A direct (loop) valid 3 × 3 cross-correlation of a 4 × 38 window with one kernel.
    fn direct_conv(x: &[f32; WINDOW_VALUES], k: &[f32; PATCH], bias: f32) -> Vec<[f32; 36]> {
        (0..CONV_ROWS)
            .map(|r| {
                core::array::from_fn(|c| {
                    let mut s = bias;
                    for i in 0..KERNEL {
                        for j in 0..KERNEL {
                            s += k[i * KERNEL + j] * x[(r + i) * WINDOW + c + j];
                        }
                    }
                    s
                })
            })
            .collect()
    }

    #[test]
    fn patch_index_on_hand_computed_cases() {
        // Patch row 0 = slot 0 (conv row 0, even column), pooled column 0 → conv (0, 0):
        // its elements are window (0,0) (0,1) (0,2) (1,0) … (2,2).
        let p0: Vec<usize> = (0..PATCH).map(|k| patch_index(0, k)).collect();
        assert_eq!(p0, [0, 1, 2, 38, 39, 40, 76, 77, 78]);
        // Patch row 18 + 5 = slot 1 (row 0, odd), pooled column 5 → conv (0, 11).
        assert_eq!(patch_index(POOLED + 5, 0), 11);
        // Slot 3 (row 1, odd), pooled column 17 → conv (1, 35); its last element is window
        // (3, 37), the last value.
        assert_eq!(patch_index(3 * POOLED + 17, 0), 38 + 35);
        assert_eq!(patch_index(3 * POOLED + 17, 8), WINDOW_VALUES - 1);
    }

    #[test]
    fn im2col_conv_equals_a_direct_convolution_and_pool_takes_window_maxima() {
        let dev = Cpu::default();
        // Hand-checkable kernels: picks the centre value; a vertical edge [-1 0 1] × 3 rows.
        let centre = [0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0];
        let edge = [-1.0, 0.0, 1.0, -1.0, 0.0, 1.0, -1.0, 0.0, 1.0];
        let x: [f32; WINDOW_VALUES] =
            core::array::from_fn(|i| ((i * 37 % 11) as f32 - 5.0) * 0.5 + (i / WINDOW) as f32);
        let mut conv = dev.build_module::<Linear<PATCH, 2>, f32>();
        let w: Vec<f32> = centre.iter().chain(&edge).copied().collect();
        conv.weight.copy_from(&w);
        conv.bias.copy_from(&[0.25, -1.0]);
        let xs: Vec<f32> = x.iter().chain(&x).copied().collect(); // a batch of 2
        let patches = Im2Col.forward(dev.tensor_from_vec(xs, (2, Const::<WINDOW_VALUES>)));
        let out = conv.forward(patches).as_vec(); // (2 · 72, 2)
        for (f, (k, b)) in [(centre, 0.25), (edge, -1.0)].iter().enumerate() {
            let direct = direct_conv(&x, k, *b);
            // Hand check of one value: centre kernel at conv (1, 4) reads window (2, 5).
            if f == 0 {
                assert_eq!(direct[1][4], x[2 * WINDOW + 5] + 0.25);
            }
            for sample in 0..2 {
                for p in 0..POSITIONS {
                    let (slot, pc) = (p / POOLED, p % POOLED);
                    let (r, c) = (slot / 2, 2 * pc + slot % 2);
                    let got = out[(sample * POSITIONS + p) * 2 + f];
                    assert!((got - direct[r][c]).abs() < 1e-5, "f{f} ({r},{c})");
                }
            }
        }
        // Pool: each output is the max of its 2 × 2 window of the direct map.
        let conv_out = dev.tensor_from_vec(out, (2 * POSITIONS, Const::<2>));
        let pooled = PoolFlatten::<2, { 2 * POOLED }>.forward(conv_out).as_vec();
        for (f, (k, b)) in [(centre, 0.25), (edge, -1.0)].iter().enumerate() {
            let d = direct_conv(&x, k, *b);
            for pc in 0..POOLED {
                let want = [
                    d[0][2 * pc],
                    d[0][2 * pc + 1],
                    d[1][2 * pc],
                    d[1][2 * pc + 1],
                ]
                .into_iter()
                .fold(f32::NEG_INFINITY, f32::max);
                assert!((pooled[pc * 2 + f] - want).abs() < 1e-5);
                assert!((pooled[POOLED * 2 + pc * 2 + f] - want).abs() < 1e-5);
            }
        }
    }
}
