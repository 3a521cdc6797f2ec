//! The softness network's weights in nalgebra, generic over the float type (feature
//! `train`): the forward pass and the Jacobian Levenberg–Marquardt trains with in `f64`
//! ([`crate::softness_train`]); inference runs on plain `f32` arrays ([`SoftnessNet`]).

#[cfg(doc)]
use crate::softness::SoftnessNet;
use crate::softness::{CLASSES, HIDDEN, N_PARAMS, N_VARIABLES};
use nalgebra::{RealField, SMatrix, SVector};

/// The network's weights: `W·h + b` per layer, `W` of shape (outputs × inputs).
#[derive(Debug, Clone, PartialEq)]
pub struct Layers<T: RealField + Copy> {
    /// Input → hidden 1.
    pub w1: SMatrix<T, HIDDEN, N_VARIABLES>,
    /// Hidden 1 bias.
    pub b1: SVector<T, HIDDEN>,
    /// Hidden 1 → hidden 2.
    pub w2: SMatrix<T, HIDDEN, HIDDEN>,
    /// Hidden 2 bias.
    pub b2: SVector<T, HIDDEN>,
    /// Hidden 2 → output.
    pub w3: SMatrix<T, CLASSES, HIDDEN>,
    /// Output bias.
    pub b3: SVector<T, CLASSES>,
}

/// The activations of one forward pass (kept for the Jacobian).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pass<T: RealField + Copy> {
    /// Hidden layer 1 (sigmoid).
    pub h1: SVector<T, HIDDEN>,
    /// Hidden layer 2 (sigmoid).
    pub h2: SVector<T, HIDDEN>,
    /// Outputs (linear).
    pub y: SVector<T, CLASSES>,
}

/// The logistic sigmoid `1 / (1 + e^-z)`: `e^-z` may overflow to `+∞`, which gives 0, so the
/// result stays in `[0, 1]` for every non-NaN `z`.
fn logistic<T: RealField + Copy>(z: T) -> T {
    T::one() / (T::one() + (-z).exp())
}

impl<T: RealField + Copy> Layers<T> {
    /// Weights from a flat parameter vector: `w1` row-major, `b1`, `w2` row-major, `b2`, `w3`
    /// row-major, `b3` (the order of [`Layers::flat`] and of the Jacobian's columns).
    pub fn from_flat(p: &[T]) -> Option<Layers<T>> {
        if p.len() != N_PARAMS {
            return None;
        }
        let mut k = 0;
        let mut take = |n: usize| {
            k += n;
            &p[k - n..k]
        };
        Some(Layers {
            w1: SMatrix::from_row_slice(take(HIDDEN * N_VARIABLES)),
            b1: SVector::from_column_slice(take(HIDDEN)),
            w2: SMatrix::from_row_slice(take(HIDDEN * HIDDEN)),
            b2: SVector::from_column_slice(take(HIDDEN)),
            w3: SMatrix::from_row_slice(take(CLASSES * HIDDEN)),
            b3: SVector::from_column_slice(take(CLASSES)),
        })
    }

    /// The flat parameter vector ([`Layers::from_flat`]'s order).
    pub fn flat(&self) -> Vec<T> {
        let mut out = Vec::with_capacity(N_PARAMS);
        out.extend(self.w1.transpose().iter());
        out.extend(self.b1.iter());
        out.extend(self.w2.transpose().iter());
        out.extend(self.b2.iter());
        out.extend(self.w3.transpose().iter());
        out.extend(self.b3.iter());
        out
    }

    /// Forward pass on a normalised input.
    pub fn forward(&self, z: &SVector<T, N_VARIABLES>) -> Pass<T> {
        let h1 = (self.w1 * z + self.b1).map(logistic);
        let h2 = (self.w2 * h1 + self.b2).map(logistic);
        let y = self.w3 * h2 + self.b3;
        Pass { h1, h2, y }
    }

    /// `∂y_k / ∂p` for every output `k` (rows) and parameter `p` (columns, flat order), by
    /// back-propagation through the sigmoid layers (`σ' = σ(1 − σ)`).
    pub fn jacobian(
        &self,
        z: &SVector<T, N_VARIABLES>,
        pass: &Pass<T>,
    ) -> SMatrix<T, CLASSES, N_PARAMS> {
        let one = T::one();
        let d1 = pass.h1.map(|h| h * (one - h));
        let d2 = pass.h2.map(|h| h * (one - h));
        let o_b1 = HIDDEN * N_VARIABLES;
        let o_w2 = o_b1 + HIDDEN;
        let o_b2 = o_w2 + HIDDEN * HIDDEN;
        let o_w3 = o_b2 + HIDDEN;
        let o_b3 = o_w3 + CLASSES * HIDDEN;
        let mut j = SMatrix::<T, CLASSES, N_PARAMS>::zeros();
        for k in 0..CLASSES {
            // δ at hidden 2 and hidden 1 for output k.
            let g2: SVector<T, HIDDEN> = SVector::from_fn(|i, _| self.w3[(k, i)] * d2[i]);
            let g1: SVector<T, HIDDEN> = (self.w2.transpose() * g2).component_mul(&d1);
            for i in 0..HIDDEN {
                j[(k, o_w3 + k * HIDDEN + i)] = pass.h2[i];
                j[(k, o_b2 + i)] = g2[i];
                j[(k, o_b1 + i)] = g1[i];
                for l in 0..HIDDEN {
                    j[(k, o_w2 + i * HIDDEN + l)] = g2[i] * pass.h1[l];
                }
                for l in 0..N_VARIABLES {
                    j[(k, i * N_VARIABLES + l)] = g1[i] * z[l];
                }
            }
            j[(k, o_b3 + k)] = one;
        }
        j
    }
}
