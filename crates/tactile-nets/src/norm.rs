//! Input standardisation shared by the models: each input minus its training mean, over its
//! training spread (population standard deviation; 1 for an input that never varies).

/// Per-input `(mean, scale)` of `rows` (training only: feature `std`); `mean` 0 and `scale` 1 when `rows` is empty.
#[cfg(feature = "train")]
pub fn mean_and_scale<const N: usize>(rows: &[[f32; N]]) -> ([f32; N], [f32; N]) {
    let mut mean = [0.0f32; N];
    let mut scale = [1.0f32; N];
    if rows.is_empty() {
        return (mean, scale);
    }
    let n = rows.len() as f64;
    for j in 0..N {
        let m = rows.iter().map(|r| f64::from(r[j])).sum::<f64>() / n;
        let var = rows
            .iter()
            .map(|r| (f64::from(r[j]) - m).powi(2))
            .sum::<f64>()
            / n;
        mean[j] = m as f32;
        scale[j] = if var.sqrt() > 1e-6 {
            var.sqrt() as f32
        } else {
            1.0
        };
    }
    (mean, scale)
}

/// `(x − mean) / scale`, element-wise.
pub fn standardise<const N: usize>(x: &[f32; N], mean: &[f32; N], scale: &[f32; N]) -> [f32; N] {
    core::array::from_fn(|j| (x[j] - mean[j]) / scale[j])
}

/// Whether every standardised value of `z` lies within `±limit` (a NaN does not). On the
/// floats' bits: a finite float's magnitude orders as its bits without the sign do, so the
/// test is an integer compare — no floating-point call on a core without an FPU.
///
/// ```
/// use tactile_nets::norm::within;
/// assert!(within(&[-4.0, 0.5, 4.0], 4.0));
/// assert!(!within(&[4.0001, 0.0], 4.0));
/// assert!(!within(&[f32::NAN], 4.0) && !within(&[f32::NEG_INFINITY], 4.0));
/// ```
pub fn within<const N: usize>(z: &[f32; N], limit: f32) -> bool {
    let limit = limit.abs().to_bits();
    z.iter().all(|v| v.to_bits() & 0x7fff_ffff <= limit)
}
