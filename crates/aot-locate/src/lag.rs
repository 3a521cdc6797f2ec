//! The ranging model's threshold lag `L = −ln(1 − θ/P)`, without a library logarithm.
//!
//! `1 − θ/P` is clamped to `[0.01, 1]`, so the logarithm only ever sees that range, where a
//! short polynomial on the float's mantissa is accurate to 2e-6 (a lag of at most 4.6 time
//! constants; the fitted `c` ≈ 25 ms makes that 0.05 µs, against 1 µs arrival resolution
//! and ≈ 400 µs per sensor conversion at OSR 256).
//! `libm::log1pf` costs a division and a few branches more, and three of them sat on every
//! localisation's critical path.

/// `θ / P` is clamped below this before `ln(1 − θ/P)`: a sensor that arrived although its
/// held rise is at or under the threshold (noise pushed it over) gets the largest lag the
/// model allows, `ln 100 ≈ 4.6` time constants, instead of an infinite one.
pub(crate) const MAX_THRESHOLD_SHARE: f32 = 0.99;

/// `L = −ln(1 − θ/P)` for a held rise `P` and threshold `θ ≥ 0`: 0 for `θ = 0`, `ln 100` for a
/// rise at or under `θ` (or not positive, or NaN).
#[inline]
pub(crate) fn threshold_lag(threshold_pa: f32, pressure_pa: f32) -> f32 {
    // Both sides computed, then selected: no branch to mispredict on the sign of `P`.
    let share = (threshold_pa / pressure_pa.max(f32::MIN_POSITIVE)).min(MAX_THRESHOLD_SHARE);
    let share = if pressure_pa > 0.0 {
        share
    } else {
        MAX_THRESHOLD_SHARE
    };
    -ln_unit(1.0 - share)
}

/// `ln x` for `x` in `[0.01, 1]` (any positive normal `x`, to the same absolute accuracy):
/// `x = 2^e · m` with `m` in `[√½, √2)`, `ln x = e·ln 2 + ln m`, and `ln(1 + f)` for
/// `f = m − 1` in `[−0.29, 0.42]` as `f·q(f)`, `q` a degree-5 least-squares polynomial on
/// Chebyshev nodes (max error 1.7e-6 there), evaluated in Estrin's form: three short chains
/// side by side instead of one of five multiply-adds in series.
#[inline]
fn ln_unit(x: f32) -> f32 {
    const C: [f32; 6] = [
        1.000_014_4,
        -0.499_844_03,
        0.332_242_1,
        -0.254_873_3,
        0.223_255_19,
        -0.142_303_8,
    ];
    // Branch-free reduction (as musl's logf): offsetting the bits by those of √½ makes the
    // exponent field count from √½, so the mantissa lands in [√½, √2) directly.
    const SQRT_HALF_BITS: u32 = 0x3f35_04f3;
    let offset = x.to_bits().wrapping_sub(SQRT_HALF_BITS);
    let e = (offset as i32) >> 23;
    let m = f32::from_bits((offset & 0x007f_ffff) + SQRT_HALF_BITS);
    let f = m - 1.0;
    let f2 = f * f;
    let q = (C[0] + C[1] * f) + f2 * ((C[2] + C[3] * f) + f2 * (C[4] + C[5] * f));
    e as f32 * core::f32::consts::LN_2 + f * q
}

#[cfg(test)]
mod tests {
    use super::*;
    use core::f32::consts::{FRAC_1_SQRT_2, SQRT_2};

    #[test]
    fn ln_matches_libm_over_the_clamped_range() {
        let mut worst = 0.0f32;
        for i in 0..=100_000 {
            let x = 0.01 + 0.99 * i as f32 / 100_000.0;
            worst = worst.max((ln_unit(x) - libm::logf(x)).abs());
        }
        assert!(worst < 2.5e-6, "max |error| {worst}");
        assert_eq!(ln_unit(1.0), 0.0);
        // Across the √½ / √2 seams of the reduction and powers of two.
        for x in [
            0.5f32,
            FRAC_1_SQRT_2.next_down(),
            FRAC_1_SQRT_2,
            FRAC_1_SQRT_2.next_up(),
            SQRT_2.next_down(),
            SQRT_2,
            SQRT_2.next_up(),
            2.0,
            0.25,
            1e-30,
            1e30,
        ] {
            assert!(
                (ln_unit(x) - libm::logf(x)).abs() < 1e-5 * (1.0 + libm::logf(x).abs()),
                "{x}"
            );
        }
    }

    #[test]
    fn lag_edges() {
        // θ = 0: no lag. θ = P/2: ln 2. At or under θ, or no rise: ln 100.
        assert_eq!(threshold_lag(0.0, 500.0), 0.0);
        assert!((threshold_lag(30.0, 60.0) - core::f32::consts::LN_2).abs() < 1e-6);
        for p in [30.0, 10.0, 0.0, -5.0, f32::NAN] {
            assert!(
                (threshold_lag(30.0, p) - libm::logf(100.0)).abs() < 1e-5,
                "{p}"
            );
        }
        assert!((threshold_lag(f32::MAX, f32::MIN_POSITIVE) - libm::logf(100.0)).abs() < 1e-5);
        assert!(threshold_lag(30.0, f32::MAX).abs() < 1e-6);
    }
}
