//! The barometer's factory calibration: four signed OTP words, each read with its CRC-8.
//!
//! Read sequence (DS-000169 §10.4; identical in TDK's and ArduPilot's reference code): send
//! [`OTP_SETUP`] (`0xC595` with OTP address `0x0066` and that address's CRC `0x9C`), then four
//! times [`OTP_READ_NEXT`] (`0xC7F7`) followed by a 3-byte read: MSB, LSB, CRC.

use crate::baro::conversion::{self, Coefficients, LutPoints, RawSample};
use crate::crc8;
use crate::error::{ConversionError, Error};

/// Command + parameter that points the OTP reader at the calibration words.
pub const OTP_SETUP: [u8; 5] = [0xC5, 0x95, 0x00, 0x66, 0x9C];
/// Command that reads the next OTP word (incremental read).
pub const OTP_READ_NEXT: [u8; 2] = [0xC7, 0xF7];

/// The four OTP constants `c0 … c3` and everything computed from them.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Calibration {
    otp: [i16; 4],
}

impl Calibration {
    /// Calibration from OTP constants already read (e.g. stored, or for tests).
    pub const fn from_otp(otp: [i16; 4]) -> Self {
        Calibration { otp }
    }

    /// Calibration from the four 3-byte OTP reads, each checked against its CRC-8.
    pub fn from_otp_reads<E>(reads: [[u8; 3]; 4]) -> Result<Self, Error<E>> {
        let mut otp = [0_i16; 4];
        for (word, read) in otp.iter_mut().zip(reads) {
            let raw = crc8::decode_word(read)
                .map_err(|(received, computed)| Error::Crc { received, computed })?;
            *word = raw as i16; // the OTP words are two's-complement
        }
        Ok(Calibration { otp })
    }

    /// The four OTP reads this calibration answers with (chip model; CRCs are valid).
    pub fn otp_reads(&self) -> [[u8; 3]; 4] {
        self.otp.map(|c| crc8::encode_word(c as u16))
    }

    /// The OTP constants `c0 … c3`.
    pub const fn otp(&self) -> [i16; 4] {
        self.otp
    }

    /// The three look-up points at temperature code `t_lsb`.
    pub fn lut_points(&self, t_lsb: u16) -> Result<LutPoints, ConversionError> {
        LutPoints::new(self.otp, t_lsb)
    }

    /// Float path: pressure in pascal (`f64`, vendor A, B, C).
    ///
    /// `raw.p_lsb` must be a 24-bit code (at most [`P_LSB_MAX`](crate::P_LSB_MAX)): a larger one
    /// cannot come from the ADC, so it is [`ConversionError::CodeOutOfRange`], never converted.
    ///
    /// ```
    /// use imu_icm20789::{Calibration, ConversionError, RawSample, P_LSB_MAX};
    /// let cal = Calibration::from_otp([1000, 2000, 3000, 4000]);
    /// let ok = RawSample { p_lsb: 9_000_000, t_lsb: 30_000 };
    /// assert!(cal.pressure_pa(ok).is_ok());
    /// let bus_fault = RawSample { p_lsb: 1 << 24, ..ok };
    /// assert_eq!(
    ///     cal.pressure_pa(bus_fault),
    ///     Err(ConversionError::CodeOutOfRange { code: 1 << 24, max: P_LSB_MAX })
    /// );
    /// ```
    pub fn pressure_pa(&self, raw: RawSample) -> Result<f64, ConversionError> {
        let p_lsb = conversion::check_p_lsb(raw.p_lsb)?;
        self.lut_points(raw.t_lsb)?
            .coefficients()?
            .pressure_pa(f64::from(p_lsb))
    }

    /// Integer path: pressure in millipascal (exact fraction, rounded once). A `raw.p_lsb`
    /// above 24 bits is [`ConversionError::CodeOutOfRange`], as for [`Self::pressure_pa`].
    pub fn pressure_milli_pa(&self, raw: RawSample) -> Result<i64, ConversionError> {
        let p_lsb = conversion::check_p_lsb(raw.p_lsb)?;
        self.lut_points(raw.t_lsb)?
            .pressure_milli_pa_scaled(i64::from(p_lsb) << conversion::QUADR_SHIFT)
    }

    /// The vendor's A, B, C at temperature code `t_lsb`.
    pub fn coefficients(&self, t_lsb: u16) -> Result<Coefficients, ConversionError> {
        self.lut_points(t_lsb)?.coefficients()
    }

    /// The raw sample a chip with this calibration reports for `pressure_pa` at `celsius`:
    /// the inverse of [`Calibration::pressure_pa`], rounded to whole codes. A pressure or
    /// temperature whose code falls outside the ADC's 24 / 16 bits gives
    /// [`ConversionError::OutOfRange`]; NaN or infinity gives [`ConversionError::NotFinite`]
    /// (there is no code for it; the chip model refuses the read).
    ///
    /// ```
    /// use imu_icm20789::{Calibration, ConversionError};
    /// let cal = Calibration::from_otp([1000, 2000, 3000, 4000]);
    /// let raw = cal.raw_for(100_000.0, 25.0)?;
    /// assert!((cal.pressure_pa(raw)? - 100_000.0).abs() < 0.1);
    /// assert_eq!(cal.raw_for(f64::INFINITY, 25.0), Err(ConversionError::NotFinite));
    /// assert_eq!(cal.raw_for(100_000.0, f32::NAN), Err(ConversionError::NotFinite));
    /// assert_eq!(cal.raw_for(100_000.0, 200.0), Err(ConversionError::OutOfRange));
    /// # Ok::<(), ConversionError>(())
    /// ```
    pub fn raw_for(&self, pressure_pa: f64, celsius: f32) -> Result<RawSample, ConversionError> {
        let t_lsb = conversion::t_lsb_exact(celsius)?;
        let x = self.coefficients(t_lsb)?.p_lsb_for(pressure_pa)?;
        let code = libm::round(x);
        if (0.0..=f64::from(conversion::P_LSB_MAX)).contains(&code) {
            Ok(RawSample {
                p_lsb: code as u32,
                t_lsb,
            })
        } else {
            Err(ConversionError::OutOfRange)
        }
    }
}
