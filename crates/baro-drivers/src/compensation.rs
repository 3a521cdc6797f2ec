//! Temperature compensation of the raw ADC codes, exactly as the MS5611-01BA03 datasheet
//! gives it (p. 7 "Pressure and temperature calculation", p. 8 "Second order temperature
//! compensation").
//!
//! All arithmetic is `i64`; every division by a power of two is an arithmetic right shift,
//! i.e. a floor, as the datasheet's integer reference implementation does. For any 24-bit D1 /
//! D2 and any 16-bit coefficients no intermediate reaches 2^62, so nothing can overflow.
//!
//! The ADC's codes are 24-bit ([`CODE_MAX`]). A larger D1 or D2 cannot come from the chip (a
//! bus fault, or a caller's bug), so it is refused with [`CompensationError::CodeOutOfRange`]
//! rather than masked to 24 bits: masking would turn the fault into a plausible reading.

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

/// The largest ADC code, D1 or D2: the MS5611 converts to 24 bits (2^24 − 1).
pub const CODE_MAX: u32 = 0x00FF_FFFF;

/// Why a pair of codes has no meaningful compensation.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum CompensationError {
    /// The corrected sensitivity SENS − SENS2 is zero or negative: pressure would fall as D1
    /// rises. Only PROM / D2 combinations far outside the chip's range produce this.
    NonPositiveSensitivity,
    /// D1 or D2 is above 24 bits, which the ADC cannot produce: a bus fault or a caller's bug.
    CodeOutOfRange {
        /// The code given (D1 if both are out of range).
        code: u32,
        /// The largest code accepted, [`CODE_MAX`].
        max: u32,
    },
}

impl core::fmt::Display for CompensationError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            CompensationError::NonPositiveSensitivity => {
                f.write_str("codes out of range: non-positive sensitivity")
            }
            CompensationError::CodeOutOfRange { code, max } => {
                write!(f, "ADC code {code:#x} is above the 24-bit maximum {max:#x}")
            }
        }
    }
}

impl core::error::Error for CompensationError {}

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
    ///
    /// D1 and D2 must be 24-bit codes (at most [`CODE_MAX`]); a larger one is
    /// [`CompensationError::CodeOutOfRange`]. A non-positive sensitivity is not checked here
    /// (the intermediates show it); [`compensate`](Self::compensate) refuses it.
    ///
    /// ```
    /// use baro_drivers::{Calibration, CompensationError, CODE_MAX};
    /// let cal = Calibration::new([40127, 36924, 23317, 23282, 33464, 28312]);
    /// assert_eq!(cal.intermediates(9_085_466, 8_569_150)?.p, 100_009);
    /// assert_eq!(
    ///     cal.intermediates(9_085_466, CODE_MAX + 1),
    ///     Err(CompensationError::CodeOutOfRange { code: CODE_MAX + 1, max: CODE_MAX })
    /// );
    /// # Ok::<(), CompensationError>(())
    /// ```
    pub fn intermediates(&self, d1: u32, d2: u32) -> Result<Intermediates, CompensationError> {
        // One compare for both codes: the OR has a bit above 24 exactly when either has.
        if (d1 | d2) > CODE_MAX {
            let code = if d1 > CODE_MAX { d1 } else { d2 };
            return Err(CompensationError::CodeOutOfRange {
                code,
                max: CODE_MAX,
            });
        }
        Ok(self.intermediates_24(d1, d2))
    }

    /// [`intermediates`](Self::intermediates) for codes known to be 24-bit (the chip model's
    /// inverse searches only those). Inlined so that a caller that needs only the temperature
    /// (the model's D2 search) leaves the pressure terms out.
    #[inline]
    pub(crate) fn intermediates_24(&self, d1: u32, d2: u32) -> Intermediates {
        let d1 = i64::from(d1);
        let d2 = i64::from(d2);

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
    ///
    /// Both codes must be 24-bit, 0 … [`CODE_MAX`]: a larger one cannot come from the ADC, so
    /// it is [`CompensationError::CodeOutOfRange`], never masked into a plausible reading.
    ///
    /// ```
    /// use baro_drivers::{Calibration, CompensationError, CODE_MAX};
    /// let cal = Calibration::new([40127, 36924, 23317, 23282, 33464, 28312]);
    /// let m = cal.compensate(9_085_466, 8_569_150)?; // the datasheet's example
    /// assert_eq!((m.temperature_centi_celsius, m.pressure_pa), (2007, 100_009));
    /// // A 25-bit D1 is a bus fault, not the code 0 it would mask to.
    /// let err = cal.compensate(0x100_0000, 8_569_150).unwrap_err();
    /// assert_eq!(err, CompensationError::CodeOutOfRange { code: 0x100_0000, max: CODE_MAX });
    /// assert_eq!(err.to_string(), "ADC code 0x1000000 is above the 24-bit maximum 0xffffff");
    /// # Ok::<(), CompensationError>(())
    /// ```
    pub fn compensate(&self, d1: u32, d2: u32) -> Result<Measurement, CompensationError> {
        let i = self.intermediates(d1, d2)?;
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
