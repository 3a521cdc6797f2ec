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
