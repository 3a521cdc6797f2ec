//! Typed IMU settings: full scales and digital low-pass filters (DS-000169 §3.1–3.2 and the
//! CONFIG / GYRO_CONFIG / ACCEL_CONFIG / ACCEL_CONFIG2 register descriptions).

/// Standard gravity, m/s² per g.
pub const STANDARD_GRAVITY: f32 = 9.806_65;

/// Accelerometer full scale (ACCEL_CONFIG.ACCEL_FS_SEL).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum AccelScale {
    /// ±2 g, 16 384 LSB/g.
    G2,
    /// ±4 g, 8 192 LSB/g.
    G4,
    /// ±8 g, 4 096 LSB/g.
    G8,
    /// ±16 g, 2 048 LSB/g.
    G16,
}

/// Gyroscope full scale (GYRO_CONFIG.FS_SEL).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum GyroScale {
    /// ±250 °/s, 131 LSB/(°/s).
    Dps250,
    /// ±500 °/s, 65.5 LSB/(°/s).
    Dps500,
    /// ±1000 °/s, 32.8 LSB/(°/s).
    Dps1000,
    /// ±2000 °/s, 16.4 LSB/(°/s).
    Dps2000,
}

/// Gyro and temperature low-pass filter (CONFIG.DLPF_CFG with FCHOICE_B = 0); 3 dB bandwidths.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum GyroDlpf {
    /// 250 Hz, 8 kHz internal rate (sample-rate divider ignored).
    Hz250,
    /// 176 Hz.
    Hz176,
    /// 92 Hz.
    Hz92,
    /// 41 Hz.
    Hz41,
    /// 20 Hz.
    Hz20,
    /// 10 Hz.
    Hz10,
    /// 5 Hz.
    Hz5,
    /// 3281 Hz, 8 kHz internal rate (sample-rate divider ignored).
    Hz3281,
}

/// Accelerometer low-pass filter (ACCEL_CONFIG2.A_DLPF_CFG with ACCEL_FCHOICE_B = 0).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum AccelDlpf {
    /// 218.1 Hz (A_DLPF_CFG = 1; 0 is the same bandwidth).
    Hz218,
    /// 99 Hz.
    Hz99,
    /// 44.8 Hz.
    Hz45,
    /// 21.2 Hz.
    Hz21,
    /// 10.2 Hz.
    Hz10,
    /// 5.1 Hz.
    Hz5,
    /// 420 Hz.
    Hz420,
}

impl AccelScale {
    /// All four full scales, smallest first.
    pub const ALL: [AccelScale; 4] = [
        AccelScale::G2,
        AccelScale::G4,
        AccelScale::G8,
        AccelScale::G16,
    ];

    /// ACCEL_FS_SEL field value (0…3).
    pub const fn bits(self) -> u8 {
        self as u8
    }

    /// The scale an ACCEL_CONFIG value selects.
    pub const fn from_register(value: u8) -> Self {
        Self::ALL[((value >> 3) & 0b11) as usize]
    }

    /// Sensitivity, LSB per g.
    pub const fn lsb_per_g(self) -> f32 {
        (16_384 >> self.bits()) as f32
    }

    /// Full scale, g.
    pub const fn full_scale_g(self) -> f32 {
        (2 << self.bits()) as f32
    }

    /// Counts → m/s².
    pub fn to_mps2(self, raw: i16) -> f32 {
        f32::from(raw) * STANDARD_GRAVITY / self.lsb_per_g()
    }

    /// m/s² → counts, rounded and saturated as the chip's ADC output saturates (chip model).
    pub fn to_raw(self, mps2: f32) -> i16 {
        saturate(mps2 / STANDARD_GRAVITY * self.lsb_per_g())
    }
}

impl GyroScale {
    /// All four full scales, smallest first.
    pub const ALL: [GyroScale; 4] = [
        GyroScale::Dps250,
        GyroScale::Dps500,
        GyroScale::Dps1000,
        GyroScale::Dps2000,
    ];

    /// FS_SEL field value (0…3).
    pub const fn bits(self) -> u8 {
        self as u8
    }

    /// The scale a GYRO_CONFIG value selects.
    pub const fn from_register(value: u8) -> Self {
        Self::ALL[((value >> 3) & 0b11) as usize]
    }

    /// Sensitivity, LSB per °/s, as the datasheet rounds it (131, 65.5, 32.8, 16.4).
    pub const fn lsb_per_dps(self) -> f32 {
        match self {
            GyroScale::Dps250 => 131.0,
            GyroScale::Dps500 => 65.5,
            GyroScale::Dps1000 => 32.8,
            GyroScale::Dps2000 => 16.4,
        }
    }

    /// Full scale, °/s.
    pub const fn full_scale_dps(self) -> f32 {
        (250 << self.bits()) as f32
    }

    /// Counts → rad/s.
    pub fn to_rps(self, raw: i16) -> f32 {
        (f32::from(raw) / self.lsb_per_dps()).to_radians()
    }

    /// rad/s → counts, rounded and saturated (chip model).
    pub fn to_raw(self, rps: f32) -> i16 {
        saturate(rps.to_degrees() * self.lsb_per_dps())
    }
}

impl GyroDlpf {
    /// DLPF_CFG field value (0…7).
    pub const fn bits(self) -> u8 {
        self as u8
    }

    /// 3 dB bandwidth, Hz.
    pub const fn bandwidth_hz(self) -> f32 {
        [250.0, 176.0, 92.0, 41.0, 20.0, 10.0, 5.0, 3281.0][self as usize]
    }

    /// Whether SMPLRT_DIV applies (1 kHz internal rate; DLPF_CFG 1…6).
    pub const fn uses_divider(self) -> bool {
        !matches!(self, GyroDlpf::Hz250 | GyroDlpf::Hz3281)
    }
}

impl AccelDlpf {
    /// A_DLPF_CFG field value (1…7).
    pub const fn bits(self) -> u8 {
        self as u8 + 1
    }

    /// 3 dB bandwidth, Hz.
    pub const fn bandwidth_hz(self) -> f32 {
        [218.1, 99.0, 44.8, 21.2, 10.2, 5.1, 420.0][self as usize]
    }
}

/// IMU temperature in °C from TEMP_OUT: `raw / 326.8 + 25` (DS-000169 §3.4, temperature
/// sensor: sensitivity 326.8 LSB/°C, 0 LSB at 25 °C).
pub fn imu_temperature_c(raw: i16) -> f32 {
    f32::from(raw) / IMU_TEMP_LSB_PER_C + 25.0
}

/// IMU temperature sensitivity, LSB/°C.
pub const IMU_TEMP_LSB_PER_C: f32 = 326.8;

/// Inverse of [`imu_temperature_c`] (chip model).
pub fn imu_temperature_raw(celsius: f32) -> i16 {
    saturate((celsius - 25.0) * IMU_TEMP_LSB_PER_C)
}

fn saturate(counts: f32) -> i16 {
    libm::roundf(counts).clamp(f32::from(i16::MIN), f32::from(i16::MAX)) as i16
}

/// Output data rate in Hz for a DLPF setting and SMPLRT_DIV value.
pub fn output_rate_hz(dlpf: GyroDlpf, divider: u8) -> f32 {
    if dlpf.uses_divider() {
        1_000.0 / (1.0 + f32::from(divider))
    } else {
        8_000.0
    }
}
