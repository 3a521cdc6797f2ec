//! Errors the chip model answers with, as a real bus would report them.

use core::fmt;

/// A bus-level failure seen by the driver talking to the model.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum SimError {
    /// No device acknowledged the I2C address.
    NoAcknowledgeAddress(u8),
    /// The chip refused a byte it has no command for.
    UnknownCommand(u8),
    /// A conversion was started while the environment's pressure or temperature was NaN or
    /// infinite: no ADC code stands for it, so the model refuses the command.
    NonFiniteConditions,
}

impl fmt::Display for SimError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SimError::NoAcknowledgeAddress(a) => write!(f, "no acknowledge at address {a:#04x}"),
            SimError::UnknownCommand(c) => write!(f, "unknown command byte {c:#04x}"),
            SimError::NonFiniteConditions => {
                f.write_str("conversion refused: the environment's conditions are not finite")
            }
        }
    }
}

impl std::error::Error for SimError {}

impl embedded_hal::i2c::Error for SimError {
    fn kind(&self) -> embedded_hal::i2c::ErrorKind {
        use embedded_hal::i2c::{ErrorKind, NoAcknowledgeSource};
        match self {
            SimError::NoAcknowledgeAddress(_) => {
                ErrorKind::NoAcknowledge(NoAcknowledgeSource::Address)
            }
            SimError::UnknownCommand(_) | SimError::NonFiniteConditions => {
                ErrorKind::NoAcknowledge(NoAcknowledgeSource::Data)
            }
        }
    }
}

impl embedded_hal::spi::Error for SimError {
    fn kind(&self) -> embedded_hal::spi::ErrorKind {
        embedded_hal::spi::ErrorKind::Other
    }
}
