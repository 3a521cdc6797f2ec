//! The contact CNN's convolution and max-pool, shared by its `'static` form
//! ([`super::StaticCnn`]) and its weights-file form (`crate::cnn_frozen`): plain arrays, no
//! `std`.

use super::{CONV_COLS, CONV_ROWS, KERNEL, PATCH, WINDOW, WINDOW_VALUES};

/// Conv columns computed together (it divides the 36 columns).
const GROUP: usize = 4;
const _: () = assert!(CONV_COLS.is_multiple_of(GROUP));

/// The max-pooled conv map of a window, `[column][filter]` as dfdx flattens it, before ReLU.
#[inline(always)]
pub(crate) fn pool<const F: usize, const FLAT: usize>(
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
