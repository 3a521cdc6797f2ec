//! `no_std` embedded-hal 1.0 driver for the TDK InvenSense **ICM-20789**: a 3-axis
//! accelerometer, 3-axis gyroscope and capacitive barometer in one package, the sensing element
//! of a multimodal tactile pad (Al & Martinez-Hernandez, "Multimodal barometric and inertial
//! measurement unit based tactile sensor for robot control", §III-A: I2C at 400 kHz, Low
//! Noise mode, 30 Hz).
//!
//! * IMU at 0x68 / 0x69: WHO_AM_I check, reset and wake-up, full scales, DLPFs, sample-rate
//!   divider, one 14-byte burst scaled to m/s², rad/s and °C, optional FIFO.
//! * Barometer at 0x63, reached through the IMU's I2C bypass: soft reset, ID check, OTP
//!   calibration with CRC-8, four modes, split-phase conversions (start, do other work, read),
//!   pressure-first or temperature-first frames, and the vendor conversion in `f64`
//!   ([`Calibration::pressure_pa`]) and in exact integers ([`Calibration::pressure_milli_pa`]).
//! * Blocking [`Icm20789`] and, with feature `async`, [`Icm20789Async`] from one source.
//! * Feature `sim`: [`sim::ChipModel`], a model of the chip on the embedded-hal I2C traits.
//!
//! # Barometer modes
//!
//! | mode | conversion typ / max | noise (rms) | current @ 1 Hz |
//! |---|---|---|---|
//! | [`BaroMode::LowPower`] | 1.6 / 1.8 ms | 3.2 Pa | 1.3 µA |
//! | [`BaroMode::Normal`] | 5.6 / 6.3 ms | 1.6 Pa | 2.6 µA |
//! | [`BaroMode::LowNoise`] | 20.8 / 23.8 ms | 0.8 Pa | 5.2 µA |
//! | [`BaroMode::UltraLowNoise`] | 83.2 / 94.5 ms | 0.4 Pa | 10.4 µA |
//!
//! Conversion times: ICM-20789 datasheet DS-000169 rev 1.4, §10 (pressure sensor operation
//! modes). Noise and current: the same table, and Al & Martinez-Hernandez §III-A. Range
//! 30…110 kPa.
//!
//! # Example: one fingertip sample, overlapping the IMU read with the pressure conversion
//!
//! ```
//! # #[cfg(not(feature = "sim"))]
//! # fn main() {}
//! # #[cfg(feature = "sim")]
//! # fn main() -> Result<(), imu_icm20789::Error<imu_icm20789::sim::SimError>> {
//! use imu_icm20789::{BaroMode, FrameOrder, Icm20789, AccelScale};
//! use imu_icm20789::sim::{ChipModel, Truth};
//! use embedded_hal::delay::DelayNs;
//!
//! // On hardware the bus is your HAL's I2C and the delay its timer; here the chip model.
//! let chip = ChipModel::new(Truth::constant([0.0, 0.0, 9.81], [0.0; 3], 101_325.0), 7);
//! let mut delay = chip.delay();
//! let mut icm = Icm20789::new_with_i2c(chip);
//! icm.init(&mut delay)?;
//! icm.set_accel_scale(AccelScale::G4)?;
//! icm.init_barometer(&mut delay)?;
//!
//! let conversion = icm.start_pressure(BaroMode::LowNoise, FrameOrder::PressureFirst)?;
//! let imu = icm.read_imu()?; // the bus is free while the barometer converts
//! delay.delay_us(conversion.wait_us()); // on hardware: do other work until then
//! let baro = icm.read_pressure(conversion)?;
//!
//! assert!((imu.accel_mps2[2] - 9.81).abs() < 0.05);
//! assert!((baro.pressure_pa - 101_325.0).abs() < 5.0);
//! # Ok(())
//! # }
//! ```
#![no_std]
#![deny(unsafe_code, missing_docs)]

#[cfg(feature = "sim")]
extern crate std;

pub mod baro;
mod crc8;
mod driver;
mod error;
pub mod imu;
#[cfg(feature = "sim")]
pub mod sim;

pub use baro::conversion::{
    Coefficients, LutPoints, P_LSB_MAX, RawSample, temperature_c, temperature_milli_c,
};
pub use baro::mode::{BaroMode, FrameOrder};
pub use baro::otp::Calibration;
pub use crc8::crc8;
#[cfg(feature = "async")]
pub use driver::Icm20789Async;
pub use driver::{BaroConversion, BaroSample, ChipFrame, Icm20789, ImuSettings};
pub use error::{ConversionError, Error};
pub use imu::config::{AccelDlpf, AccelScale, GyroDlpf, GyroScale};
pub use imu::{ImuAddress, ImuSample, RawImu};
