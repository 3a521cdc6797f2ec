//! T-norms (fuzzy AND, implication) and S-norms (fuzzy OR, aggregation).
//!
//! Definitions follow fuzzylite, whose names they keep; MATLAB's `min`, `prod`, `max`,
//! `probor` and `sum` are among them.

use crate::Real;

/// A T-norm: conjunction of antecedents, or implication (how a rule's strength shapes its
/// consequent term).
///
/// ```
/// use fuzzy_mamdani::TNorm;
/// assert_eq!(TNorm::Minimum.apply(0.3, 0.6), 0.3);
/// assert!((TNorm::AlgebraicProduct.apply(0.5, 0.6) - 0.3f64).abs() < 1e-15);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum TNorm {
    /// `min(a, b)` (MATLAB `min`).
    Minimum,
    /// `a · b` (MATLAB `prod`).
    AlgebraicProduct,
    /// Łukasiewicz `max(0, a + b − 1)`.
    BoundedDifference,
    /// `b` if `a = 1`, `a` if `b = 1`, else 0.
    DrasticProduct,
    /// `a b / (2 − (a + b − a b))`.
    EinsteinProduct,
    /// `a b / (a + b − a b)`, 0 when both are 0.
    HamacherProduct,
    /// `min(a, b)` if `a + b > 1`, else 0 (fuzzylite's nilpotent minimum).
    NilpotentMinimum,
}

/// An S-norm: disjunction of antecedents, or aggregation of the implied consequents.
///
/// ```
/// use fuzzy_mamdani::SNorm;
/// assert_eq!(SNorm::Maximum.apply(0.3, 0.6), 0.6);
/// assert!((SNorm::AlgebraicSum.apply(0.5, 0.5) - 0.75f64).abs() < 1e-15);
/// assert_eq!(SNorm::UnboundedSum.apply(0.75, 0.5), 1.25); // MATLAB's `sum` aggregation
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum SNorm {
    /// `max(a, b)` (MATLAB `max`).
    Maximum,
    /// Probabilistic sum `a + b − a b` (MATLAB `probor`).
    AlgebraicSum,
    /// `min(1, a + b)`.
    BoundedSum,
    /// `b` if `a = 0`, `a` if `b = 0`, else 1.
    DrasticSum,
    /// `(a + b) / (1 + a b)`.
    EinsteinSum,
    /// `(a + b − 2 a b) / (1 − a b)`, 1 when `a b = 1`.
    HamacherSum,
    /// `a + b`, unbounded (MATLAB `sum` aggregation; not a true S-norm).
    UnboundedSum,
    /// `max(a, b)` if `a + b < 1`, else 1 (fuzzylite's nilpotent maximum).
    NilpotentMaximum,
    /// `(a + b) / max(1, a + b)` (fuzzylite's normalized sum).
    NormalizedSum,
}

impl TNorm {
    /// Every T-norm, for exhaustive tests and pickers.
    pub const ALL: [TNorm; 7] = [
        TNorm::Minimum,
        TNorm::AlgebraicProduct,
        TNorm::BoundedDifference,
        TNorm::DrasticProduct,
        TNorm::EinsteinProduct,
        TNorm::HamacherProduct,
        TNorm::NilpotentMinimum,
    ];

    /// The T-norm of `a` and `b`.
    #[inline]
    pub fn apply<T: Real>(self, a: T, b: T) -> T {
        let one = T::one();
        let zero = T::zero();
        match self {
            TNorm::Minimum => a.min(b),
            TNorm::AlgebraicProduct => a * b,
            TNorm::BoundedDifference => (a + b - one).max(zero),
            TNorm::DrasticProduct => {
                if a.max(b) == one {
                    a.min(b)
                } else {
                    zero
                }
            }
            TNorm::EinsteinProduct => a * b / (one + one - (a + b - a * b)),
            TNorm::HamacherProduct => {
                let d = a + b - a * b;
                if d == zero { zero } else { a * b / d }
            }
            TNorm::NilpotentMinimum => {
                if a + b > one {
                    a.min(b)
                } else {
                    zero
                }
            }
        }
    }
}

impl SNorm {
    /// Every S-norm, for exhaustive tests and pickers.
    pub const ALL: [SNorm; 9] = [
        SNorm::Maximum,
        SNorm::AlgebraicSum,
        SNorm::BoundedSum,
        SNorm::DrasticSum,
        SNorm::EinsteinSum,
        SNorm::HamacherSum,
        SNorm::UnboundedSum,
        SNorm::NilpotentMaximum,
        SNorm::NormalizedSum,
    ];

    /// The S-norm of `a` and `b`.
    #[inline]
    pub fn apply<T: Real>(self, a: T, b: T) -> T {
        let one = T::one();
        let zero = T::zero();
        match self {
            SNorm::Maximum => a.max(b),
            SNorm::AlgebraicSum => a + b - a * b,
            SNorm::BoundedSum => (a + b).min(one),
            SNorm::DrasticSum => {
                if a.min(b) == zero {
                    a.max(b)
                } else {
                    one
                }
            }
            SNorm::EinsteinSum => (a + b) / (one + a * b),
            SNorm::HamacherSum => {
                let ab = a * b;
                if ab == one {
                    one
                } else {
                    (a + b - ab - ab) / (one - ab)
                }
            }
            SNorm::UnboundedSum => a + b,
            SNorm::NilpotentMaximum => {
                if a + b < one {
                    a.max(b)
                } else {
                    one
                }
            }
            SNorm::NormalizedSum => (a + b) / (a + b).max(one),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn t_norms_have_one_as_identity_and_zero_as_annihilator() {
        for t in TNorm::ALL {
            for a in [0.0, 0.25, 0.5, 1.0f64] {
                assert!((t.apply(a, 1.0) - a).abs() < 1e-15, "{t:?}({a}, 1)");
                assert_eq!(t.apply(a, 0.0), 0.0, "{t:?}({a}, 0)");
            }
        }
    }

    #[test]
    fn s_norms_have_zero_as_identity() {
        for s in SNorm::ALL {
            for a in [0.0, 0.25, 0.5, 1.0f64] {
                assert!((s.apply(a, 0.0) - a).abs() < 1e-15, "{s:?}({a}, 0)");
            }
        }
        for s in SNorm::ALL.into_iter().filter(|s| *s != SNorm::UnboundedSum) {
            assert_eq!(s.apply(0.3, 1.0), 1.0, "{s:?}(0.3, 1)");
        }
    }

    #[test]
    fn fuzzylite_reference_values() {
        // fuzzylite's definitions at (0.4, 0.7).
        let (a, b) = (0.4f64, 0.7);
        assert!((TNorm::EinsteinProduct.apply(a, b) - 0.28 / (2.0 - 0.82)).abs() < 1e-15);
        assert!((TNorm::HamacherProduct.apply(a, b) - 0.28 / 0.82).abs() < 1e-15);
        assert!((TNorm::BoundedDifference.apply(a, b) - 0.1).abs() < 1e-15);
        assert!((SNorm::EinsteinSum.apply(a, b) - 1.1 / 1.28).abs() < 1e-15);
        assert!((SNorm::HamacherSum.apply(a, b) - (1.1 - 0.56) / 0.72).abs() < 1e-15);
        assert_eq!(SNorm::DrasticSum.apply(a, b), 1.0);
        assert_eq!(TNorm::DrasticProduct.apply(a, b), 0.0);
        assert_eq!(TNorm::NilpotentMinimum.apply(a, b), 0.4);
        assert_eq!(TNorm::NilpotentMinimum.apply(0.2, 0.7), 0.0);
        assert_eq!(SNorm::NilpotentMaximum.apply(0.2, 0.7), 0.7);
        assert_eq!(SNorm::NilpotentMaximum.apply(a, b), 1.0);
        assert!((SNorm::NormalizedSum.apply(a, b) - 1.0).abs() < 1e-15);
        assert!((SNorm::NormalizedSum.apply(0.2f64, 0.3) - 0.5).abs() < 1e-15);
    }
}
