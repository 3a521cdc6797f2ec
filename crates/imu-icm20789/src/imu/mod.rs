//! The 6-axis IMU at I2C address 0x68 / 0x69: registers, settings and scaling.

pub mod config;
pub mod registers;

/// The IMU's 7-bit I2C address, chosen by the AD0 pin.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ImuAddress {
    /// AD0 low: 0x68.
    Ad0Low,
    /// AD0 high: 0x69.
    Ad0High,
}

impl ImuAddress {
    /// The 7-bit address.
    pub const fn addr(self) -> u8 {
        match self {
            ImuAddress::Ad0Low => 0x68,
            ImuAddress::Ad0High => 0x69,
        }
    }
}

/// One IMU burst (ACCEL_XOUT_H … GYRO_ZOUT_L) as counts.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct RawImu {
    /// Accelerometer x, y, z counts.
    pub accel: [i16; 3],
    /// TEMP_OUT counts.
    pub temp: i16,
    /// Gyroscope x, y, z counts.
    pub gyro: [i16; 3],
}

/// Bytes in the data burst.
pub const BURST_LEN: usize = 14;

impl RawImu {
    /// Decodes the 14 big-endian data bytes.
    pub fn from_bytes(b: &[u8; BURST_LEN]) -> Self {
        let w = |i: usize| i16::from_be_bytes([b[2 * i], b[2 * i + 1]]);
        RawImu {
            accel: [w(0), w(1), w(2)],
            temp: w(3),
            gyro: [w(4), w(5), w(6)],
        }
    }

    /// Encodes as the chip lays the data registers out (chip model).
    pub fn to_bytes(&self) -> [u8; BURST_LEN] {
        let mut out = [0_u8; BURST_LEN];
        let words = [
            self.accel[0],
            self.accel[1],
            self.accel[2],
            self.temp,
            self.gyro[0],
            self.gyro[1],
            self.gyro[2],
        ];
        for (chunk, w) in out.chunks_exact_mut(2).zip(words) {
            chunk.copy_from_slice(&w.to_be_bytes());
        }
        out
    }
}

/// One IMU sample in SI units.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ImuSample {
    /// Acceleration (specific force) along x, y, z, m/s².
    pub accel_mps2: [f32; 3],
    /// Angular rate about x, y, z, rad/s.
    pub gyro_rps: [f32; 3],
    /// Die temperature, °C.
    pub temperature_c: f32,
}
