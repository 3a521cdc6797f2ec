//! The 270° potentiometer on each distal joint (seed 001 §2.3), wired as a voltage divider and
//! read by the same 10-bit ADC: linear, 270/1024 ≈ 0.26° per code.

use super::Adc;
use serde::Deserialize;
use underactuated_hand::calibration::PotMount;

/// A linear rotary potentiometer mounted so that joint angle 0 sits at `zero_deg` of its travel.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Pot {
    /// Electrical travel, degrees (seed 001 §2.3: 270°).
    pub travel_deg: f64,
    /// Where on its travel the open (0°) joint sits, degrees; the 90° joint range then stays
    /// well inside the travel, as the paper notes.
    pub zero_deg: f64,
}

impl Default for Pot {
    fn default() -> Self {
        Pot {
            travel_deg: 270.0,
            zero_deg: 45.0,
        }
    }
}

impl Pot {
    /// Wiper voltage for joint angle `angle_rad` with a mounting error `offset_deg`, supply `vcc_v`.
    pub fn volts(&self, angle_rad: f64, offset_deg: f64, vcc_v: f64) -> f64 {
        let shaft = self.zero_deg + angle_rad.to_degrees() + offset_deg;
        vcc_v * (shaft / self.travel_deg).clamp(0.0, 1.0)
    }

    /// The joint angle a code stands for, rad, by the nominal mounting.
    ///
    /// ```
    /// use hand_sim::underactuated::{Adc, Pot};
    /// let (pot, adc) = (Pot::default(), Adc::default());
    /// let code = adc.code(pot.volts(0.5, 0.0, adc.vref_v));
    /// assert!((pot.decode(&adc, code) - 0.5).abs() < 270f64.to_radians() / 1024.0);
    /// ```
    pub fn decode(&self, adc: &Adc, code: u16) -> f64 {
        self.angle_from_volts(adc.volts(code), adc.vref_v)
    }

    /// The joint angle a wiper voltage `v` stands for with supply `vcc_v`, rad, by the
    /// nominal mounting (the inverse of [`volts`](Self::volts) without mounting error).
    ///
    /// ```
    /// use hand_sim::underactuated::Pot;
    /// let pot = Pot::default();
    /// assert!((pot.angle_from_volts(pot.volts(0.7, 0.0, 5.0), 5.0) - 0.7).abs() < 1e-12);
    /// ```
    pub fn angle_from_volts(&self, v: f64, vcc_v: f64) -> f64 {
        PotMount {
            travel_deg: self.travel_deg,
            zero_deg: self.zero_deg,
        }
        .angle_deg(v, vcc_v)
        .to_radians()
    }
}
