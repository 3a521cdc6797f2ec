//! Temperature compensation of the raw ADC codes, exactly as the MS5611-01BA03 datasheet
//! gives it (p. 7 "Pressure and temperature calculation", p. 8 "Second order temperature
//! compensation").
//!
//! All arithmetic is `i64`; every division by a power of two is an arithmetic right shift,
//! i.e. a floor, as the datasheet's integer reference implementation does. For any 24-bit D1 /
//! D2 and any 16-bit coefficients no intermediate reaches 2^62, so nothing can overflow.

/// One compensated reading in the datasheet's integer units.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Measurement {
    /// Temperature in 0.01 °C (2007 = 20.07 °C).
    pub temperature_centi_celsius: i32,
    /// Pressure in Pa, i.e. 0.01 mbar (100009 = 1000.09 mbar).
    pub pressure_pa: i32,
}

impl Measurement {
    /// Temperature in °C.
    pub fn temperature_celsius(&self) -> f32 {
        self.temperature_centi_celsius as f32 / 100.0
    }

    /// Pressure in mbar (hPa).
    pub fn pressure_mbar(&self) -> f32 {
        self.pressure_pa as f32 / 100.0
    }
}

/// Every intermediate of the datasheet calculation, for checking against its worked example
/// and for diagnostics.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Intermediates {
    /// dT = D2 − C5·2^8.
    pub dt: i64,
    /// First-order TEMP = 2000 + dT·C6/2^23 (0.01 °C).
    pub temp: i64,
    /// First-order OFF = C2·2^16 + C4·dT/2^7.
    pub off: i64,
    /// First-order SENS = C1·2^15 + C3·dT/2^8.
    pub sens: i64,
    /// Second-order temperature correction T2 (0 at or above 20 °C).
    pub t2: i64,
    /// Second-order offset correction OFF2.
    pub off2: i64,
    /// Second-order sensitivity correction SENS2.
    pub sens2: i64,
    /// Final pressure P = (D1·(SENS−SENS2)/2^21 − (OFF−OFF2))/2^15 (Pa).
    pub p: i64,
}

impl Intermediates {
    /// The final temperature, TEMP − T2 (0.01 °C).
    pub fn temperature(&self) -> i64 {
        self.temp - self.t2
    }
}

/// Why a pair of codes has no meaningful compensation.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum CompensationError {
    /// The corrected sensitivity SENS − SENS2 is zero or negative: pressure would fall as D1
    /// rises. Only PROM / D2 combinations far outside the chip's range produce this.
    NonPositiveSensitivity,
}

/// The six factory coefficients C1 … C6 (datasheet p. 7, "Read calibration data").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Calibration {
    c: [u16; 6],
}

impl Calibration {
    /// Coefficients C1 … C6 in datasheet order. Prefer [`crate::Prom::calibration`], which
    /// checks the CRC first.
    pub const fn new(coefficients: [u16; 6]) -> Self {
        Self { c: coefficients }
    }

    /// The coefficients C1 … C6.
    pub const fn coefficients(&self) -> [u16; 6] {
        self.c
    }

    fn coef(&self, n: usize) -> i64 {
        i64::from(self.c[n - 1])
    }

    /// The whole calculation with every intermediate, first and second order.
    pub fn intermediates(&self, d1: u32, d2: u32) -> Intermediates {
        // Codes are 24-bit; masking keeps the no-overflow bound true for any u32 input.
        let d1 = i64::from(d1 & 0x00FF_FFFF);
        let d2 = i64::from(d2 & 0x00FF_FFFF);

        let dt = d2 - (self.coef(5) << 8);
        let temp = 2000 + ((dt * self.coef(6)) >> 23);
        let off = (self.coef(2) << 16) + ((self.coef(4) * dt) >> 7);
        let sens = (self.coef(1) << 15) + ((self.coef(3) * dt) >> 8);

        // Second order, MS5611 coefficients (not the MS5637's 3·dT²/2^33 family).
        let (mut t2, mut off2, mut sens2) = (0, 0, 0);
        if temp < 2000 {
            let below20 = (temp - 2000) * (temp - 2000);
            t2 = (dt * dt) >> 31;
            off2 = (5 * below20) >> 1;
            sens2 = (5 * below20) >> 2;
            if temp < -1500 {
                let below_m15 = (temp + 1500) * (temp + 1500);
                off2 += 7 * below_m15;
                sens2 += (11 * below_m15) >> 1;
            }
        }

        let p = (((d1 * (sens - sens2)) >> 21) - (off - off2)) >> 15;
        Intermediates {
            dt,
            temp,
            off,
            sens,
            t2,
            off2,
            sens2,
            p,
        }
    }

    /// Compensated temperature and pressure from D1 (pressure code) and D2 (temperature code).
    pub fn compensate(&self, d1: u32, d2: u32) -> Result<Measurement, CompensationError> {
        let i = self.intermediates(d1, d2);
        if i.sens - i.sens2 <= 0 {
            return Err(CompensationError::NonPositiveSensitivity);
        }
        Ok(Measurement {
            temperature_centi_celsius: saturate_i32(i.temperature()),
            pressure_pa: saturate_i32(i.p),
        })
    }
}

/// The bounds above keep both results well inside `i32` (|TEMP| < 2^18, and |P| < 2^23 whenever the sensitivity is positive); this
/// only makes the narrowing total instead of panicking.
fn saturate_i32(v: i64) -> i32 {
    i32::try_from(v).unwrap_or(if v < 0 { i32::MIN } else { i32::MAX })
}
