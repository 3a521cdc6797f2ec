//! Output activations evaluated outside the graph, stable for any logit (huge, infinite).
//!
//! The networks end in a linear layer and are trained on logits (dfdx's
//! `*_with_logits` losses); these turn logits into probabilities at inference time.
//! Transcendentals go through `num_traits::Float`: std's on a host, libm's without `std`.

use num_traits::Float;

/// The logistic function `1 / (1 + e^-x)`, in `0.0..=1.0` for every non-NaN `x`.
///
/// Never forms `e^x` for positive `x`, so it cannot overflow; NaN stays NaN.
pub fn sigmoid(x: f32) -> f32 {
    if x >= 0.0 {
        1.0 / (1.0 + Float::exp(-x))
    } else {
        let e = Float::exp(x);
        e / (1.0 + e)
    }
}

/// `ln(sigmoid(x))`, finite for every finite `x` (`-x` for very negative `x`).
pub fn log_sigmoid(x: f32) -> f32 {
    // ln σ(x) = -softplus(-x) = min(x, 0) - ln(1 + e^-|x|)
    x.min(0.0) - Float::ln_1p(Float::exp(-x.abs()))
}

/// Softmax of `logits` into `out` (same length), max-subtracted so it cannot overflow.
///
/// Infinite logits: the `+∞` entries share the mass equally; all `-∞` gives a uniform
/// distribution. Returns `false` (and leaves `out` unspecified) when the lengths differ,
/// `logits` is empty or holds a NaN.
pub fn softmax_into(logits: &[f32], out: &mut [f32]) -> bool {
    if logits.is_empty() || logits.len() != out.len() || logits.iter().any(|v| v.is_nan()) {
        return false;
    }
    let max = logits.iter().copied().fold(f32::NEG_INFINITY, f32::max);
    if max.is_infinite() {
        let hits = logits.iter().filter(|&&v| v == max).count() as f32;
        for (o, &v) in out.iter_mut().zip(logits) {
            *o = if v == max { 1.0 / hits } else { 0.0 };
        }
        return true;
    }
    let mut sum = 0.0f32;
    for (o, &v) in out.iter_mut().zip(logits) {
        // v - max ≤ 0 and the max term is exactly 1, so sum ∈ [1, n].
        *o = Float::exp(v - max);
        sum += *o;
    }
    for o in out.iter_mut() {
        *o /= sum;
    }
    true
}

/// Softmax of `logits` as a new vector; `None` when empty or holding a NaN.
#[cfg(feature = "std")]
pub fn softmax(logits: &[f32]) -> Option<Vec<f32>> {
    let mut out = vec![0.0; logits.len()];
    softmax_into(logits, &mut out).then_some(out)
}
