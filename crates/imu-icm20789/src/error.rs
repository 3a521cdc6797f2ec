//! The driver's one error type, with the bus error inside, and the conversion's own errors.

/// Why a raw barometer sample has no pressure.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum ConversionError {
    /// The OTP constants at this temperature put two look-up points on top of each other or
    /// all three on one line, so no curve `P = A + B / (C + p)` passes through them (a zero
    /// denominator in the vendor's A, B, C formulas).
    DegenerateCalibration,
    /// `C + p_LSB = 0`: the raw code sits on the curve's pole.
    Pole,
    /// The result does not fit its output: the integer pressure (only near the pole of a
    /// nonsensical OTP set), or, for the inverse ([`crate::Calibration::raw_for`]), a code
    /// outside the ADC's 24 bits (pressure) or 16 bits (temperature).
    OutOfRange,
    /// A pressure code above 24 bits, which the ADC cannot produce: a bus fault or a caller's
    /// bug, refused rather than converted into a plausible pressure.
    CodeOutOfRange {
        /// The code given.
        code: u32,
        /// The largest code accepted, [`crate::P_LSB_MAX`].
        max: u32,
    },
    /// A NaN or infinite pressure or temperature given to the inverse: no code stands for it.
    NotFinite,
}

/// All errors of the ICM-20789 driver; `E` is the I2C bus error.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum Error<E> {
    /// The bus reported an error (a NACK, e.g. reading the barometer before its conversion ended).
    I2c(E),
    /// WHO_AM_I (0x75) held neither 0x03 (ICM-20789) nor 0x02 (its rev R1).
    WrongImuId(u8),
    /// The barometer's ID word had `id & 0x3F != 0x08`; the whole word is kept.
    WrongBaroId(u16),
    /// A barometer word failed its CRC-8.
    Crc {
        /// CRC byte on the wire.
        received: u8,
        /// CRC computed over the two data bytes.
        computed: u8,
    },
    /// The calibration cannot convert this sample.
    Conversion(ConversionError),
    /// A pressure was to be converted before `init_barometer` read the calibration.
    BaroNotInitialised,
}

impl<E> From<ConversionError> for Error<E> {
    fn from(e: ConversionError) -> Self {
        Error::Conversion(e)
    }
}

impl core::fmt::Display for ConversionError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(match self {
            ConversionError::DegenerateCalibration => "calibration points are degenerate",
            ConversionError::Pole => "raw pressure code is on the conversion's pole",
            ConversionError::OutOfRange => "converted pressure does not fit the output type",
            ConversionError::CodeOutOfRange { code, max } => {
                return write!(
                    f,
                    "raw pressure code {code:#x} is above the 24-bit maximum {max:#x}"
                );
            }
            ConversionError::NotFinite => "pressure or temperature is not a finite number",
        })
    }
}

impl<E: core::fmt::Debug> core::fmt::Display for Error<E> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Error::I2c(e) => write!(f, "I2C error: {e:?}"),
            Error::WrongImuId(id) => write!(f, "unexpected WHO_AM_I {id:#04x}"),
            Error::WrongBaroId(id) => write!(f, "unexpected barometer ID word {id:#06x}"),
            Error::Crc { received, computed } => {
                write!(
                    f,
                    "CRC-8 mismatch: received {received:#04x}, computed {computed:#04x}"
                )
            }
            Error::Conversion(e) => write!(f, "pressure conversion: {e}"),
            Error::BaroNotInitialised => f.write_str("barometer calibration not read yet"),
        }
    }
}

impl core::error::Error for ConversionError {}
impl<E: core::fmt::Debug> core::error::Error for Error<E> {}
