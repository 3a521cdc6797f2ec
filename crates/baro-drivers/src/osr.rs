//! Oversampling ratio: the MS5611's speed / accuracy knob.

use core::time::Duration;

/// Oversampling ratio of one ADC conversion (D1 pressure or D2 temperature).
///
/// Figures are from the MS5611-01BA03 datasheet (DA5611-01BA03, p. 2 "Performance
/// specifications" and p. 3 "Electrical characteristics / ADC"): a higher ratio
/// converts longer and is quieter.
///
/// | OSR  | conversion typ / max | pressure RMS noise | temperature RMS noise |
/// |------|----------------------|--------------------|-----------------------|
/// | 256  | 0.54 / 0.60 ms       | 0.065 mbar         | 0.012 °C              |
/// | 512  | 1.06 / 1.17 ms       | 0.042 mbar         | 0.008 °C              |
/// | 1024 | 2.08 / 2.28 ms       | 0.027 mbar         | 0.005 °C              |
/// | 2048 | 4.13 / 4.54 ms       | 0.018 mbar         | 0.003 °C              |
/// | 4096 | 8.22 / 9.04 ms       | 0.012 mbar         | 0.002 °C              |
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Default)]
pub enum Osr {
    /// 256 samples: fastest, noisiest.
    Osr256,
    /// 512 samples.
    Osr512,
    /// 1024 samples.
    Osr1024,
    /// 2048 samples.
    Osr2048,
    /// 4096 samples: slowest, quietest (the default).
    #[default]
    Osr4096,
}

impl Osr {
    /// Every ratio, fastest first.
    pub const ALL: [Osr; 5] = [
        Osr::Osr256,
        Osr::Osr512,
        Osr::Osr1024,
        Osr::Osr2048,
        Osr::Osr4096,
    ];

    fn index(self) -> usize {
        self as usize
    }

    /// The ratio `ratio` (256 … 4096), or `None` when the MS5611 has no such ratio.
    ///
    /// ```
    /// use baro_drivers::Osr;
    /// assert_eq!(Osr::from_ratio(1024), Some(Osr::Osr1024));
    /// assert_eq!(Osr::from_ratio(300), None);
    /// ```
    pub fn from_ratio(ratio: u16) -> Option<Osr> {
        Osr::ALL.into_iter().find(|o| o.ratio() == ratio)
    }

    /// The ratio as a number (256 … 4096).
    pub const fn ratio(self) -> u16 {
        256 << (self as u16)
    }

    /// Offset added to the D1 / D2 conversion command (0x40 / 0x50 + offset).
    pub const fn command_offset(self) -> u8 {
        2 * (self as u8)
    }

    /// Typical conversion time in nanoseconds.
    pub fn conversion_time_typ_ns(self) -> u32 {
        [540_000, 1_060_000, 2_080_000, 4_130_000, 8_220_000][self.index()]
    }

    /// Maximum conversion time in nanoseconds: how long a reader must wait after a convert
    /// command before the ADC result is valid.
    pub fn conversion_time_max_ns(self) -> u32 {
        [600_000, 1_170_000, 2_280_000, 4_540_000, 9_040_000][self.index()]
    }

    /// Maximum conversion time as a [`Duration`].
    pub fn conversion_time_max(self) -> Duration {
        Duration::from_nanos(u64::from(self.conversion_time_max_ns()))
    }

    /// RMS pressure noise (datasheet "resolution") in mbar.
    pub fn pressure_noise_rms_mbar(self) -> f32 {
        [0.065, 0.042, 0.027, 0.018, 0.012][self.index()]
    }

    /// RMS temperature noise (datasheet "resolution") in °C.
    pub fn temperature_noise_rms_celsius(self) -> f32 {
        [0.012, 0.008, 0.005, 0.003, 0.002][self.index()]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ratios_and_command_offsets_follow_the_command_table() {
        let got: [(u16, u8); 5] = Osr::ALL.map(|o| (o.ratio(), o.command_offset()));
        assert_eq!(got, [(256, 0), (512, 2), (1024, 4), (2048, 6), (4096, 8)]);
    }

    #[test]
    fn slower_ratios_are_quieter() {
        for pair in Osr::ALL.windows(2) {
            assert!(pair[0].conversion_time_max_ns() < pair[1].conversion_time_max_ns());
            assert!(pair[0].conversion_time_typ_ns() < pair[0].conversion_time_max_ns());
            assert!(pair[0].pressure_noise_rms_mbar() > pair[1].pressure_noise_rms_mbar());
            assert!(
                pair[0].temperature_noise_rms_celsius() > pair[1].temperature_noise_rms_celsius()
            );
        }
    }
}
