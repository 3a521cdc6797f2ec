//! Timestamped frames that tactile sources produce.

/// `N` barometric pressures read at one instant, e.g. the three MS5611 of a fingertip.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PressureFrame<const N: usize> {
    /// When the frame was read, in microseconds of the source's clock (simulated or real).
    pub t_us: u64,
    /// One absolute pressure per sensor, in pascal, in the pad geometry's sensor order.
    pub pressure_pa: [f32; N],
}

/// One sample of a combined inertial + barometric chip such as the ICM-20789.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ImuFrame {
    /// When the frame was read, in microseconds of the source's clock.
    pub t_us: u64,
    /// Acceleration along the chip's x, y, z axes, in m/s².
    pub accel_mps2: [f32; 3],
    /// Angular rate about the chip's x, y, z axes, in rad/s.
    pub gyro_rps: [f32; 3],
    /// Absolute pressure in pascal, when a conversion finished for this frame.
    pub pressure_pa: Option<f32>,
}

/// One sample of an `N`-finger hand with a force sensor and a distal-joint angle per finger.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FingerFrame<const N: usize> {
    /// When the frame was read, in microseconds of the source's clock.
    pub t_us: u64,
    /// Normal force on each finger's force sensor, in newton.
    pub force_n: [f32; N],
    /// Each finger's distal joint angle, in radians.
    pub distal_angle_rad: [f32; N],
}
