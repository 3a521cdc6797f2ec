//! The CNN's layers on stable dfdx: the im2col patch index on hand-computed cases, and im2col
//! with a dense layer equals a direct convolution, pooled to its 2 × 2 window maxima.

use dfdx::nn::modules::Module;
use dfdx::prelude::*;
use tactile_nets::cnn_layers::{
    CONV_ROWS, Im2Col, KERNEL, PATCH, POOLED, POSITIONS, PoolFlatten, patch_index,
};
use tactile_nets::contact_cnn::{WINDOW, WINDOW_VALUES};

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
