//! Axis ranges and tick labels shared by every chart the crate draws (the report's inline
//! SVGs and `papers trade`'s files), so both read data the same way.

use std::ops::Range;

/// A number for people: four significant digits, no exponent for everyday magnitudes.
pub fn fmt_num(v: f64) -> String {
    if !v.is_finite() {
        return format!("{v}");
    }
    if v == 0.0 {
        return "0".into();
    }
    let mag = v.abs().log10().floor() as i32;
    if !(-4..=7).contains(&mag) {
        return format!("{v:.3e}");
    }
    let decimals = (3 - mag).clamp(0, 6) as usize;
    let s = format!("{v:.decimals$}");
    // Trailing zeros after the point say nothing.
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_owned()
    } else {
        s
    }
}

/// `lo..hi` of the finite values, widened when empty or a single value.
pub fn span(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
    if lo > hi {
        (0.0, 1.0)
    } else if hi - lo <= f64::EPSILON * lo.abs().max(1.0) {
        (lo - 0.5, hi + 0.5)
    } else {
        (lo, hi)
    }
}

/// The span with 4 % of its width added on each side, so end points are not on the frame.
pub fn padded((lo, hi): (f64, f64)) -> Range<f64> {
    let pad = 0.04 * (hi - lo);
    lo - pad..hi + pad
}

/// Whether positive values spanning `lo..hi` read better on a log axis: two decades or more
/// (costs from nanoseconds to milliseconds).
pub fn wants_log((lo, hi): (f64, f64)) -> bool {
    lo > 0.0 && hi / lo >= 100.0
}

/// An axis tick: [`fmt_num`], with rounding noise around zero (`-2.2e-16`) shown as `0`.
pub fn fmt_tick(v: f64, axis: &Range<f64>) -> String {
    if v.abs() <= 1e-9 * (axis.end - axis.start).abs() {
        "0".into()
    } else {
        fmt_num(v)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spans_survive_empty_constant_and_nan_data() {
        assert_eq!(span(std::iter::empty()), (0.0, 1.0));
        assert_eq!(span([2.0, 2.0].into_iter()), (1.5, 2.5));
        assert_eq!(span([f64::NAN, 1.0, 3.0].into_iter()), (1.0, 3.0));
    }

    #[test]
    fn numbers_keep_four_significant_digits() {
        assert_eq!(fmt_num(0.0), "0");
        assert_eq!(fmt_num(95.8333), "95.83");
        assert_eq!(fmt_num(1023.0), "1023");
        assert_eq!(fmt_num(0.012345), "0.01235");
        assert_eq!(fmt_num(-2.5), "-2.5");
        assert_eq!(fmt_num(1.5e9), "1.500e9");
        assert_eq!(fmt_num(f64::NAN), "NaN");
    }

    #[test]
    fn ticks_pads_and_log_choice() {
        assert_eq!(fmt_tick(-2.2e-16, &(-1.0..1.0)), "0");
        assert!(wants_log((0.1, 10.0)) && !wants_log((1.0, 99.0)) && !wants_log((-1.0, 1e3)));
        assert_eq!(padded((0.0, 100.0)), -4.0..104.0);
    }
}
