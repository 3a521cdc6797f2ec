//! The fixed-point forms' quantisation rule and its integer conversions, in one copy: `build.rs`
//! applies it to the built-in models' weights at build time (it includes this file), the
//! `quantise` functions of [`crate::fixed`] to a model's weights at run time, so both give the
//! same integers. Integer work on the floats' bits: no `std`, no floating-point library call.

/// The largest magnitude a quantised weight takes (`i16`).
pub(crate) const WEIGHT_LIMIT: i64 = 32767;
/// The largest magnitude a quantised bias takes (`i32`, with headroom for the sum it joins).
pub(crate) const BIAS_LIMIT: i64 = 1 << 30;
/// Exponents stay within what the fixed-point layers shift by.
pub(crate) const MAX_EXP: i32 = 60;

/// The exponent `e` a tensor is stored at: the largest `e ≤ MAX_EXP` with
/// `max |x| · 2^e ≤ limit` (`limit` below `2^31`). An all-zero tensor has no scale to choose
/// (its zeros are exact at any exponent): `MAX_EXP`, where the products of a weight tensor of
/// zeros meet the layer's bias without rounding it. The values must be finite (the callers
/// check).
pub(crate) fn scale_exp(values: &[f32], limit: i64) -> i32 {
    // Finite magnitudes order as their bits.
    let top = values
        .iter()
        .map(|v| v.to_bits() & 0x7fff_ffff)
        .max()
        .unwrap_or(0);
    if top == 0 {
        return MAX_EXP;
    }
    // |max| = m · 2^(b − 150), the mantissa with its implicit 1 (none for a subnormal).
    let biased = (top >> 23) as i32;
    let (m, b) = if biased == 0 {
        (i64::from(top), 1)
    } else {
        (i64::from((top & 0x7f_ffff) | 0x80_0000), biased)
    };
    // The largest k with m · 2^k ≤ limit is one of two neighbours of the bit lengths' gap.
    let bits = |x: i64| 64 - x.leading_zeros() as i32;
    let mut k = bits(limit) - bits(m);
    let fits = |k: i32| {
        if k >= 0 {
            m << k <= limit
        } else {
            m <= limit << -k
        }
    };
    if !fits(k) {
        k -= 1;
    }
    (k - (b - 150)).min(MAX_EXP)
}

/// `round(x · 2^exp)`, halves away from zero, from `x`'s bits (0 for zero and subnormals;
/// finite `x`, and `x · 2^exp` within `i64`).
pub(crate) fn fixed_of(x: f32, exp: i32) -> i64 {
    let bits = x.to_bits();
    let biased = ((bits >> 23) & 0xff) as i32;
    if biased == 0 {
        return 0;
    }
    // |x| = mantissa · 2^(biased − 150), the mantissa with its implicit leading 1.
    let mantissa = i64::from((bits & 0x7f_ffff) | 0x80_0000);
    let magnitude = shift(mantissa, biased - 150 + exp);
    if bits >> 31 == 1 {
        -magnitude
    } else {
        magnitude
    }
}

/// `x · 2^by`: a left shift, or a right shift rounding half up; 0 past 62 bits right. The
/// callers keep `x · 2^by` within `i64` (a shift of 64 bits or more saturates; a smaller one
/// that does not fit would wrap): the one conversion that may exceed it, a layer's
/// accumulators into the logistic table's input, saturates on its own.
#[inline]
pub(crate) fn shift(x: i64, by: i32) -> i64 {
    if by >= 0 {
        x.checked_shl(by as u32).unwrap_or(match x {
            0 => 0,
            x if x < 0 => i64::MIN,
            _ => i64::MAX,
        })
    } else if by > -63 {
        let s = (-by) as u32;
        (x + (1 << (s - 1))) >> s
    } else {
        0
    }
}
