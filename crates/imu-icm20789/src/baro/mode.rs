//! The barometer's four measurement modes and the order of the two results in a frame.
//!
//! | mode | command P first | command T first | conversion typ / max | noise (rms) | current @ 1 Hz |
//! |---|---|---|---|---|---|
//! | [`BaroMode::LowPower`] (LP) | `0x401A` | `0x609C` | 1.6 / 1.8 ms | 3.2 Pa | 1.3 µA |
//! | [`BaroMode::Normal`] (N) | `0x48A3` | `0x6825` | 5.6 / 6.3 ms | 1.6 Pa | 2.6 µA |
//! | [`BaroMode::LowNoise`] (LN) | `0x5059` | `0x70DF` | 20.8 / 23.8 ms | 0.8 Pa | 5.2 µA |
//! | [`BaroMode::UltraLowNoise`] (ULN) | `0x58E0` | `0x7866` | 83.2 / 94.5 ms | 0.4 Pa | 10.4 µA |
//!
//! Sources: ICM-20789 datasheet DS-000169 rev 1.4, §10 (pressure sensor measurement commands
//! and the operation-mode table: conversion time, noise, current); noise and current also in
//! the multimodal-pad paper (Al & Martinez-Hernandez, "Multimodal barometric and inertial
//! measurement unit based tactile sensor for robot control", §III-A: "Low Power (3.2 Pa
//! noise, 1.3 µA), Normal (1.6 Pa, 2.6 µA), Low Noise (0.8 Pa, 5.2 µA), Ultra Low Noise
//! (0.4 Pa, 10.4 µA)"). The
//! command codes agree with TDK's and ArduPilot's reference drivers (`0x401A`, `0x5059`,
//! `0x609C`, `0x70DF` appear there verbatim). The maximum conversion times equal the waits
//! (1800 / 6300 / 23800 / 94500 µs) that TDK InvenSense's own Linux IIO driver for the same
//! barometer core uses (`drivers/iio/pressure/icp10100.c`, `icp10100_cmd_measure`); the typical
//! times have not been checked against the datasheet PDF, so nothing here waits only for them.

/// Pressure measurement mode: speed and current against noise.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Deserialize))]
pub enum BaroMode {
    /// LP: 1.8 ms worst-case conversion, 3.2 Pa rms noise.
    LowPower,
    /// N: 6.3 ms worst-case conversion, 1.6 Pa rms noise.
    Normal,
    /// LN: 23.8 ms worst-case conversion, 0.8 Pa rms noise (the mode the pad paper used).
    LowNoise,
    /// ULN: 94.5 ms worst-case conversion, 0.4 Pa rms noise.
    UltraLowNoise,
}

/// Which result the chip transmits first in the 9-byte measurement frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum FrameOrder {
    /// Pressure (3 data bytes in two CRC words) then temperature (one CRC word).
    PressureFirst,
    /// Temperature (one CRC word) then pressure (two CRC words).
    TemperatureFirst,
}

impl BaroMode {
    /// All four modes, fastest first.
    pub const ALL: [BaroMode; 4] = [
        BaroMode::LowPower,
        BaroMode::Normal,
        BaroMode::LowNoise,
        BaroMode::UltraLowNoise,
    ];

    /// The 16-bit command that starts a conversion in this mode with the given frame order.
    pub const fn command(self, order: FrameOrder) -> u16 {
        match (self, order) {
            (BaroMode::LowPower, FrameOrder::PressureFirst) => 0x401A,
            (BaroMode::Normal, FrameOrder::PressureFirst) => 0x48A3,
            (BaroMode::LowNoise, FrameOrder::PressureFirst) => 0x5059,
            (BaroMode::UltraLowNoise, FrameOrder::PressureFirst) => 0x58E0,
            (BaroMode::LowPower, FrameOrder::TemperatureFirst) => 0x609C,
            (BaroMode::Normal, FrameOrder::TemperatureFirst) => 0x6825,
            (BaroMode::LowNoise, FrameOrder::TemperatureFirst) => 0x70DF,
            (BaroMode::UltraLowNoise, FrameOrder::TemperatureFirst) => 0x7866,
        }
    }

    /// The mode and order a measurement command selects, if it is one.
    pub fn from_command(command: u16) -> Option<(BaroMode, FrameOrder)> {
        BaroMode::ALL.into_iter().find_map(|mode| {
            [FrameOrder::PressureFirst, FrameOrder::TemperatureFirst]
                .into_iter()
                .find(|&order| mode.command(order) == command)
                .map(|order| (mode, order))
        })
    }

    /// Typical conversion time in microseconds (DS-000169 §10 mode table).
    pub const fn conversion_time_typ_us(self) -> u32 {
        match self {
            BaroMode::LowPower => 1_600,
            BaroMode::Normal => 5_600,
            BaroMode::LowNoise => 20_800,
            BaroMode::UltraLowNoise => 83_200,
        }
    }

    /// Maximum conversion time in microseconds: wait at least this long before reading.
    pub const fn conversion_time_max_us(self) -> u32 {
        match self {
            BaroMode::LowPower => 1_800,
            BaroMode::Normal => 6_300,
            BaroMode::LowNoise => 23_800,
            BaroMode::UltraLowNoise => 94_500,
        }
    }

    /// Pressure noise in pascal rms (DS-000169 §10; Al & Martinez-Hernandez §III-A).
    pub const fn noise_pa_rms(self) -> f32 {
        match self {
            BaroMode::LowPower => 3.2,
            BaroMode::Normal => 1.6,
            BaroMode::LowNoise => 0.8,
            BaroMode::UltraLowNoise => 0.4,
        }
    }

    /// Supply current in microampere at one measurement per second (same sources).
    pub const fn current_ua_at_1hz(self) -> f32 {
        match self {
            BaroMode::LowPower => 1.3,
            BaroMode::Normal => 2.6,
            BaroMode::LowNoise => 5.2,
            BaroMode::UltraLowNoise => 10.4,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn commands_are_distinct_and_decode_back() {
        let mut seen = [0_u16; 8];
        let mut n = 0;
        for mode in BaroMode::ALL {
            for order in [FrameOrder::PressureFirst, FrameOrder::TemperatureFirst] {
                let cmd = mode.command(order);
                assert!(!seen[..n].contains(&cmd));
                seen[n] = cmd;
                n += 1;
                assert_eq!(BaroMode::from_command(cmd), Some((mode, order)));
            }
        }
        assert_eq!(BaroMode::from_command(0x805D), None); // soft reset is not a measurement
    }

    #[test]
    fn each_slower_mode_halves_noise_and_doubles_current() {
        // Al & Martinez-Hernandez's four figures (§III-A) follow this ladder exactly.
        for pair in BaroMode::ALL.windows(2) {
            assert_eq!(pair[0].noise_pa_rms(), 2.0 * pair[1].noise_pa_rms());
            assert_eq!(
                2.0 * pair[0].current_ua_at_1hz(),
                pair[1].current_ua_at_1hz()
            );
            assert!(pair[0].conversion_time_max_us() < pair[1].conversion_time_max_us());
            assert!(pair[0].conversion_time_typ_us() < pair[0].conversion_time_max_us());
        }
    }
}
