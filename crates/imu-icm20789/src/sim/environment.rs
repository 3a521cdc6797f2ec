//! What the simulated chip senses: a trait (or any closure) giving the true state over time.

/// The physical truth at one instant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TrueState {
    /// Specific force along the chip's x, y, z axes, m/s² (gravity included: +9.81 on z at rest).
    pub accel_mps2: [f32; 3],
    /// Angular rate about x, y, z, rad/s.
    pub gyro_rps: [f32; 3],
    /// Absolute pressure on the barometer, Pa.
    pub pressure_pa: f64,
    /// Die temperature, °C.
    pub temperature_c: f32,
}

/// Source of the truth the chip model measures; `hand-sim` implements it for a fingertip pad.
///
/// Any `FnMut(u64) -> TrueState` (argument: simulated time in µs) is an environment.
pub trait Environment {
    /// The true state at simulated time `t_us`.
    fn state(&mut self, t_us: u64) -> TrueState;
}

impl<F: FnMut(u64) -> TrueState> Environment for F {
    fn state(&mut self, t_us: u64) -> TrueState {
        self(t_us)
    }
}

/// An environment that never changes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Truth(pub TrueState);

impl Truth {
    /// Constant acceleration, rotation rate and pressure at 25 °C.
    pub fn constant(accel_mps2: [f32; 3], gyro_rps: [f32; 3], pressure_pa: f64) -> Self {
        Truth(TrueState {
            accel_mps2,
            gyro_rps,
            pressure_pa,
            temperature_c: 25.0,
        })
    }

    /// The same, at another temperature.
    pub fn at_temperature(mut self, celsius: f32) -> Self {
        self.0.temperature_c = celsius;
        self
    }
}

impl Environment for Truth {
    fn state(&mut self, _t_us: u64) -> TrueState {
        self.0
    }
}
