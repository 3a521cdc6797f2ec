//! How long bus transfers take in simulated time.

/// Bus clock rates; each transfer advances the shared clock by its bit count at this rate.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct BusTiming {
    /// I2C SCL frequency (the MS5611 and TCA9548A allow up to 400 kHz).
    pub i2c_hz: u32,
    /// SPI SCLK frequency (the MS5611 allows up to 20 MHz).
    pub spi_hz: u32,
}

impl Default for BusTiming {
    fn default() -> Self {
        Self {
            i2c_hz: 400_000,
            spi_hz: 20_000_000,
        }
    }
}

impl BusTiming {
    /// Zero-duration transfers, to look at conversion timing alone.
    pub const INSTANT: BusTiming = BusTiming {
        i2c_hz: 0,
        spi_hz: 0,
    };

    fn ns(bits: u64, hz: u32) -> u64 {
        if hz == 0 {
            0
        } else {
            bits * 1_000_000_000 / u64::from(hz)
        }
    }

    /// One I2C message of `bytes` data bytes: start, address + R/W, the data (9 clocks a
    /// byte with the acknowledge), stop.
    pub fn i2c_message_ns(&self, bytes: usize) -> u64 {
        Self::ns(2 + 9 * (1 + bytes as u64), self.i2c_hz)
    }

    /// `bytes` bytes clocked over SPI.
    pub fn spi_bytes_ns(&self, bytes: usize) -> u64 {
        Self::ns(8 * bytes as u64, self.spi_hz)
    }
}
