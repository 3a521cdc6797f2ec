//! The quadratic base of [`Head::Centroid`](super::Head::Centroid): a least-squares fit of the
//! centroid on the three standardised log rises and their products, which the network then
//! corrects (it learns the residual).
//!
//! Why: the pad's Gaussian spread makes each log rise nearly quadratic in position, and the
//! sensors' saturation bends it. A ReLU network of 64 and 32 units draws that smooth surface
//! in straight pieces, and at the fractions of a millimetre a cell border asks for, the
//! pieces show. With the smooth part fitted in closed form, the network only draws the
//! smaller remainder.

use super::N_FEATURES;

/// Terms of the base: a constant, the three standardised log rises, and their six squares
/// and products.
pub const BASE_TERMS: usize = 10;

/// The base's terms at the standardised inputs `z` (the log rises are `z[0..3]`).
pub fn base_terms(z: &[f32; N_FEATURES]) -> [f32; BASE_TERMS] {
    let [a, b, c] = [z[0], z[1], z[2]];
    [1.0, a, b, c, a * a, a * b, a * c, b * b, b * c, c * c]
}

/// A fitted quadratic base: one row of [`BASE_TERMS`] coefficients per centroid coordinate
/// (row, column), cell units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct QuadraticBase {
    /// Coefficients of [`base_terms`], per output.
    pub coef: [[f32; BASE_TERMS]; 2],
}

impl QuadraticBase {
    /// The base's centroid at the standardised inputs `z`.
    pub fn at(&self, z: &[f32; N_FEATURES]) -> [f32; 2] {
        let t = base_terms(z);
        core::array::from_fn(|o| self.coef[o].iter().zip(&t).map(|(w, x)| w * x).sum())
    }

    /// The least-squares base of `targets` at the standardised inputs `rows` (the minimum-norm
    /// solution when the terms are not independent, as on a handful of taps); `None` for no
    /// rows or a non-finite fit.
    #[cfg(feature = "train")]
    pub fn fit(rows: &[[f32; N_FEATURES]], targets: &[[f32; 2]]) -> Option<QuadraticBase> {
        use nalgebra::DMatrix;
        if rows.is_empty() || rows.len() != targets.len() {
            return None;
        }
        let x = DMatrix::from_fn(rows.len(), BASE_TERMS, |i, j| {
            f64::from(base_terms(&rows[i])[j])
        });
        let y = DMatrix::from_fn(targets.len(), 2, |i, o| f64::from(targets[i][o]));
        let w = x.svd(true, true).solve(&y, 1e-9).ok()?;
        let coef = core::array::from_fn(|o| core::array::from_fn(|j| w[(j, o)] as f32));
        coef.iter()
            .flatten()
            .all(|c: &f32| c.is_finite())
            .then_some(QuadraticBase { coef })
    }
}
