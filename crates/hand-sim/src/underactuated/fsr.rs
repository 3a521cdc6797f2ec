//! The force sensing resistor on each distal phalanx (seed 001 §2.2: striped SF10-60, reading
//! range 10 g – 5 kg) in a voltage divider read by the 10-bit ADC.
//!
//! Law (stated, not published by the paper): a polymer-thick-film FSR's resistance falls as a
//! power of force, `R(F) = R₁ · (F / 1 kgf)^(−k)` with `R₁ = 3 kΩ`, `k = 0.9` (Interlink's FSR
//! integration guide shows conductance nearly proportional to force, `k ≈ 1`); below the
//! rated 10 g floor the strip is open (`R_open = 10 MΩ`); above 5 kg its reading saturates.
//! Divider: FSR from Vcc to the ADC pin, `R_m = 10 kΩ` to ground, `V = Vcc·R_m / (R_m + R)`.

use super::Adc;
use serde::Deserialize;
use underactuated_hand::calibration::FsrLaw;

/// One kilogram-force, N.
pub use underactuated_hand::calibration::KGF_N;

/// The FSR's force → resistance law and its divider.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Fsr {
    /// Resistance at 1 kgf, Ω.
    pub r_1kgf_ohm: f64,
    /// Power-law exponent `k` in `R ∝ F^(−k)`.
    pub exponent: f64,
    /// Resistance below the rated floor (no contact), Ω.
    pub r_open_ohm: f64,
    /// Rated floor, N (seed 001 §2.2: 10 g).
    pub min_force_n: f64,
    /// Rated ceiling, N, where the reading saturates (seed 001 §2.2: 5 kg).
    pub max_force_n: f64,
    /// Divider resistor to ground, Ω.
    pub divider_ohm: f64,
}

impl Default for Fsr {
    fn default() -> Self {
        Fsr {
            r_1kgf_ohm: 3_000.0,
            exponent: 0.9,
            r_open_ohm: 10.0e6,
            min_force_n: 0.010 * KGF_N,
            max_force_n: 5.0 * KGF_N,
            divider_ohm: 10_000.0,
        }
    }
}

impl Fsr {
    /// The strip's resistance under `force_n` for a unit whose sensitivity is `gain` times
    /// nominal (unit-to-unit spread; 1 = nominal).
    pub fn resistance(&self, force_n: f64, gain: f64) -> f64 {
        if force_n.is_nan() || force_n < self.min_force_n {
            return self.r_open_ohm;
        }
        let f = force_n.min(self.max_force_n) * gain.max(1e-6);
        self.r_1kgf_ohm * (f / KGF_N).powf(-self.exponent)
    }

    /// The divider's output voltage for `force_n`, with supply `vcc_v`.
    pub fn volts(&self, force_n: f64, gain: f64, vcc_v: f64) -> f64 {
        vcc_v * self.divider_ohm / (self.divider_ohm + self.resistance(force_n, gain))
    }

    /// The force a code stands for, by the nominal law (the Arduino-side calibration): 0 below
    /// the rated floor, the ceiling at or above it; always finite.
    ///
    /// ```
    /// use hand_sim::underactuated::{Adc, Fsr};
    /// let (fsr, adc) = (Fsr::default(), Adc::default());
    /// let code = adc.code(fsr.volts(10.0, 1.0, adc.vref_v));
    /// assert!((fsr.decode(&adc, code) - 10.0).abs() < 0.1);
    /// assert_eq!(fsr.decode(&adc, 0), 0.0);
    /// ```
    pub fn decode(&self, adc: &Adc, code: u16) -> f64 {
        self.force_from_volts(adc.volts(code), adc.vref_v)
    }

    /// The force a divider voltage `v` stands for with supply `vcc_v`, by the nominal law (the
    /// inverse of [`volts`](Self::volts) at unit gain): 0 below the rated floor, the ceiling
    /// at or above it; always finite.
    ///
    /// ```
    /// use hand_sim::underactuated::Fsr;
    /// let fsr = Fsr::default();
    /// assert!((fsr.force_from_volts(fsr.volts(20.0, 1.0, 5.0), 5.0) - 20.0).abs() < 1e-9);
    /// assert_eq!(fsr.force_from_volts(0.0, 5.0), 0.0);
    /// assert_eq!(fsr.force_from_volts(5.0, 5.0), fsr.max_force_n);
    /// ```
    pub fn force_from_volts(&self, v: f64, vcc_v: f64) -> f64 {
        self.law().force_n(v, vcc_v)
    }

    /// The calibration a user of the real hand states for this strip (underactuated-hand's
    /// law, whose inverse the hand's readings go through).
    pub fn law(&self) -> FsrLaw {
        FsrLaw {
            r_1kgf_ohm: self.r_1kgf_ohm,
            exponent: self.exponent,
            divider_ohm: self.divider_ohm,
            min_force_n: self.min_force_n,
            max_force_n: self.max_force_n,
        }
    }
}
