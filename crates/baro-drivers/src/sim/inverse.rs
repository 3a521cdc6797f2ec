//! ADC codes for given true conditions: the datasheet compensation run backwards by bisection
//! over the forward code, so model and driver share one formula.
//!
//! A true value beyond what the codes express saturates at the end code, as the ADC does;
//! a non-finite one has no code at all (NaN would otherwise cast to the code for 0).

use crate::compensation::{CODE_MAX, Calibration};

/// Smallest code in 1 … 2^24 − 1 for which `reaches(code)` holds (the top code if none);
/// `reaches` must be monotone (false … false true … true).
fn bisect(reaches: impl Fn(u32) -> bool) -> u32 {
    let (mut lo, mut hi) = (1, CODE_MAX);
    while lo < hi {
        let mid = lo + (hi - lo) / 2;
        if reaches(mid) {
            hi = mid;
        } else {
            lo = mid + 1;
        }
    }
    lo
}

/// The D2 code whose compensated temperature is `temperature_centi` (0.01 °C), rounded;
/// `None` when it is not finite.
pub(crate) fn temperature_code(cal: &Calibration, temperature_centi: f64) -> Option<u32> {
    let target = finite_target(temperature_centi)?;
    Some(bisect(|d2| {
        cal.intermediates_24(0, d2).temperature() >= target
    }))
}

/// The D1 code whose compensated pressure, with temperature code `d2` (24-bit), is
/// `pressure_pa`, rounded; `None` when it is not finite.
pub(crate) fn pressure_code(cal: &Calibration, d2: u32, pressure_pa: f64) -> Option<u32> {
    let target = finite_target(pressure_pa)?;
    let d2 = d2.min(CODE_MAX);
    Some(bisect(|d1| cal.intermediates_24(d1, d2).p >= target))
}

/// `value` rounded to an integer target (saturating), or `None` if it is NaN or infinite.
fn finite_target(value: f64) -> Option<i64> {
    value.is_finite().then(|| value.round() as i64)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::DATASHEET_COEFFICIENTS;

    /// NaN or infinite °C has no code (not the code for 0.00 °C, nor the end code).
    #[test]
    fn non_finite_truth_has_no_code_and_finite_extremes_saturate() {
        let cal = Calibration::new(DATASHEET_COEFFICIENTS);
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            assert_eq!(temperature_code(&cal, bad), None);
            assert_eq!(pressure_code(&cal, 8_569_150, bad), None);
        }
        assert_eq!(temperature_code(&cal, 1e300), Some(CODE_MAX));
        assert_eq!(pressure_code(&cal, 8_569_150, -1e300), Some(1));
        let d2 = temperature_code(&cal, 2007.0).expect("finite");
        assert_eq!(cal.intermediates_24(0, d2).temperature(), 2007);
        assert_eq!(cal.intermediates_24(0, d2 - 1).temperature(), 2006);
    }
}
