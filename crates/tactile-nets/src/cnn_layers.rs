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

use crate::contact_cnn::{WINDOW, WINDOW_VALUES};
use dfdx::nn::modules::{Module, NonMutableModule, ZeroSizedModule};
use dfdx::prelude::*;

pub use crate::contact_cnn::{CONV_COLS, CONV_ROWS, KERNEL, PATCH, POOL_SLOTS, POOLED, POSITIONS};

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
