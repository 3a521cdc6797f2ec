//! ADC codes for given true conditions: the datasheet compensation run backwards by bisection
//! over the forward code, so model and driver share one formula.

use crate::compensation::Calibration;

/// Largest 24-bit code.
const CODE_MAX: u32 = 0x00FF_FFFF;

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

/// The D2 code whose compensated temperature is `temperature_centi` (0.01 °C), rounded.
pub(crate) fn temperature_code(cal: &Calibration, temperature_centi: f64) -> u32 {
    let target = temperature_centi.round() as i64;
    bisect(|d2| cal.intermediates(0, d2).temperature() >= target)
}

/// The D1 code whose compensated pressure, with temperature code `d2`, is `pressure_pa`,
/// rounded.
pub(crate) fn pressure_code(cal: &Calibration, d2: u32, pressure_pa: f64) -> u32 {
    let target = pressure_pa.round() as i64;
    bisect(|d1| cal.intermediates(d1, d2).p >= target)
}
