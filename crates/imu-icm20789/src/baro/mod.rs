//! The barometer at I2C address 0x63: commands, modes, frames, OTP calibration and conversion.

pub mod conversion;
pub mod frame;
pub mod mode;
pub mod otp;

/// The barometer's fixed 7-bit I2C address (reached through the IMU's bypass).
pub const BARO_ADDRESS: u8 = 0x63;
/// Soft reset command.
pub const SOFT_RESET: [u8; 2] = [0x80, 0x5D];
/// Read-ID command; answered by one CRC word whose low six bits are [`BARO_ID`].
pub const READ_ID: [u8; 2] = [0xEF, 0xC8];
/// Product-specific bits of the ID word (`id & 0x3F`).
pub const BARO_ID: u16 = 0x08;
/// Wait after a soft reset before the next command, µs: the 10 ms that TDK's and ArduPilot's
/// reference drivers use.
pub const SOFT_RESET_TIME_US: u32 = 10_000;
