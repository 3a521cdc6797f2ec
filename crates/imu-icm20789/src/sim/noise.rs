//! Seeded measurement noise of the chip model.

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};

/// Noise the model adds before quantising.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SimNoise {
    /// Accelerometer white noise per axis and sample, m/s² rms.
    pub accel_mps2_rms: f32,
    /// Gyroscope white noise per axis and sample, rad/s rms.
    pub gyro_rps_rms: f32,
    /// Multiplier of each barometer mode's datasheet noise ([`crate::BaroMode::noise_pa_rms`]).
    pub pressure_noise_scale: f32,
}

impl SimNoise {
    /// No noise: the model returns the truth, quantised.
    pub const NONE: SimNoise = SimNoise {
        accel_mps2_rms: 0.0,
        gyro_rps_rms: 0.0,
        pressure_noise_scale: 0.0,
    };
}

impl Default for SimNoise {
    /// Barometer at its datasheet noise per mode. IMU: 0.02 m/s² and 0.0015 rad/s rms, which are
    /// simulation parameters of the order of MEMS IMU noise densities over a ~100 Hz band, not
    /// ICM-20789 datasheet figures.
    fn default() -> Self {
        SimNoise {
            accel_mps2_rms: 0.02,
            gyro_rps_rms: 0.0015,
            pressure_noise_scale: 1.0,
        }
    }
}

/// A seeded Gaussian source.
#[derive(Debug, Clone)]
pub(crate) struct NoiseSource {
    rng: ChaCha8Rng,
}

impl NoiseSource {
    pub(crate) fn new(seed: u64) -> Self {
        NoiseSource {
            rng: ChaCha8Rng::seed_from_u64(seed),
        }
    }

    /// One draw of N(0, σ²); exactly 0 when σ is 0 (or not a valid deviation).
    pub(crate) fn gaussian(&mut self, sigma: f64) -> f64 {
        match Normal::new(0.0, sigma) {
            Ok(normal) if sigma > 0.0 => normal.sample(&mut self.rng),
            _ => 0.0,
        }
    }
}
