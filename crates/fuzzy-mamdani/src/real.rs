//! The floating-point types the engine is generic over.

use num_traits::Float;

/// A floating-point scalar the engine computes in: `f32` or `f64`.
///
/// Only `f32` and `f64` implement it; the conversions are exact for `f64` and round to nearest
/// for `f32`, so a file or a builder written with `f64` literals builds either engine.
pub trait Real:
    Float + core::fmt::Debug + core::fmt::Display + Default + Send + Sync + 'static
{
    /// `x` converted (rounded to nearest for `f32`).
    fn of(x: f64) -> Self;
    /// The value as `f64` (exact).
    fn to_f64_lossless(self) -> f64;
}

impl Real for f32 {
    fn of(x: f64) -> Self {
        x as f32
    }
    fn to_f64_lossless(self) -> f64 {
        f64::from(self)
    }
}

impl Real for f64 {
    fn of(x: f64) -> Self {
        x
    }
    fn to_f64_lossless(self) -> f64 {
        self
    }
}
