//! The driver's one error type.

use core::fmt;

use crate::compensation::CompensationError;
use crate::prom::PromError;

/// Everything a driver call can fail with; `E` is the bus (I2C or SPI) error.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum Error<E> {
    /// The bus transfer failed (NACK, arbitration, …).
    Comm(E),
    /// The PROM read back was blank or failed its CRC-4.
    Prom(PromError),
    /// The ADC read returned 0: the conversion had not finished (or none was running). The
    /// chip answers 0 in that case, and a conversion interrupted by an early read is lost.
    AdcNotReady,
    /// `read_result` was called with no conversion started.
    NoConversionStarted,
    /// A pressure was compensated before any temperature code was read.
    NoTemperature,
    /// The codes cannot be compensated (see [`CompensationError`]).
    Compensation(CompensationError),
}

impl<E> From<PromError> for Error<E> {
    fn from(e: PromError) -> Self {
        Error::Prom(e)
    }
}

impl<E> From<CompensationError> for Error<E> {
    fn from(e: CompensationError) -> Self {
        Error::Compensation(e)
    }
}

impl<E: fmt::Debug> fmt::Display for Error<E> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::Comm(e) => write!(f, "bus error: {e:?}"),
            Error::Prom(PromError::Crc { stored, computed }) => write!(
                f,
                "PROM CRC-4 mismatch: stored {stored:#x}, computed {computed:#x}"
            ),
            Error::Prom(PromError::Blank) => f.write_str("PROM blank: no chip answered"),
            Error::AdcNotReady => f.write_str("ADC read before the conversion finished"),
            Error::NoConversionStarted => f.write_str("no conversion started"),
            Error::NoTemperature => f.write_str("no temperature code read yet"),
            Error::Compensation(e) => write!(f, "{e}"),
        }
    }
}

impl<E: fmt::Debug> core::error::Error for Error<E> {}

/// A failed mode change: the error and the device, handed back unchanged so the caller
/// keeps its bus.
#[derive(Debug)]
pub struct ModeChangeError<E, DEV> {
    /// What went wrong.
    pub error: E,
    /// The device in its previous mode.
    pub dev: DEV,
}
