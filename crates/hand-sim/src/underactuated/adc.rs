//! The Arduino's 10-bit successive-approximation ADC (seed 001 §3.2): every reading of the hand
//! leaves the model as a code in 0…1023, like `analogRead`.

use serde::Deserialize;

/// The largest code of a 10-bit converter.
pub const ADC_MAX_CODE: u16 = 1023;

/// A 10-bit ADC with reference `vref_v`: `code = floor(V / Vref · 1024)`, clamped to 0…1023.
///
/// ```
/// use hand_sim::underactuated::Adc;
/// let adc = Adc::default();
/// assert_eq!(adc.code(0.0), 0);
/// assert_eq!(adc.code(2.5), 512);
/// assert_eq!(adc.code(9.0), 1023);
/// assert_eq!(adc.code(f64::NAN), 0);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Adc {
    /// Reference (and supply) voltage, V: the Arduino Uno's 5 V default.
    pub vref_v: f64,
}

impl Default for Adc {
    fn default() -> Self {
        Adc { vref_v: 5.0 }
    }
}

impl Adc {
    /// The code for input voltage `v` (NaN and negative read 0, over-range reads 1023).
    pub fn code(&self, v: f64) -> u16 {
        let x = (v / self.vref_v * 1024.0).floor();
        if x.is_nan() || x <= 0.0 {
            0
        } else if x >= f64::from(ADC_MAX_CODE) {
            ADC_MAX_CODE
        } else {
            x as u16
        }
    }

    /// The voltage a code stands for: the middle of its bin, so decoding is unbiased.
    pub fn volts(&self, code: u16) -> f64 {
        underactuated_hand::calibration::adc_volts(code, self.vref_v)
    }
}
