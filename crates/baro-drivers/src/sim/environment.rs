//! What the simulated chip senses: true pressure and temperature over simulated time.

/// True conditions at the sensor.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Conditions {
    /// Absolute pressure in mbar (datasheet range 10 … 1200).
    pub pressure_mbar: f64,
    /// Temperature in °C (datasheet range −40 … 85).
    pub temperature_celsius: f64,
}

/// A source of true conditions; a physics simulator implements this (or passes a closure
/// `FnMut(now_ns) -> Conditions`) to drive the chip model.
pub trait Environment {
    /// The conditions at simulated time `now_ns`.
    fn conditions(&mut self, now_ns: u64) -> Conditions;
}

/// Constant conditions.
impl Environment for Conditions {
    fn conditions(&mut self, _now_ns: u64) -> Conditions {
        *self
    }
}

impl<F: FnMut(u64) -> Conditions> Environment for F {
    fn conditions(&mut self, now_ns: u64) -> Conditions {
        self(now_ns)
    }
}
