//! Typed errors: each names the board by its port and says what failed.

use crate::parser::FrameError;

/// What failed talking to a board; [`Error`] adds the port.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ErrorKind {
    /// The awaited message did not arrive in time.
    #[error("no {waiting_for} within {timeout_ms} ms{}", seen(*.frame_errors))]
    Timeout {
        /// What was awaited ("protocol version report", "I2C reply from 0x77", …).
        waiting_for: String,
        /// How long, ms.
        timeout_ms: u64,
        /// Bytes that did not frame as Firmata meanwhile.
        frame_errors: u64,
    },
    /// Bytes arrived after the port opened but none was a Firmata version report: another
    /// sketch, or a board at another baud rate (line noise looks like this too).
    #[error(
        "not answering as Firmata at {baud} baud: {bytes} bytes arrived, none a version report \
         (first: {sample}); is it another sketch, or Firmata at another baud rate?"
    )]
    NotFirmata {
        /// The baud rate the port was opened at.
        baud: u32,
        /// How many bytes arrived.
        bytes: u64,
        /// The first bytes, as text where printable and hex otherwise.
        sample: String,
    },
    /// The awaited sysex arrived cut short or garbled (bytes lost on the line).
    #[error("{0}")]
    Garbled(FrameError),
    /// The firmware refused the request with a string message, e.g. ConfigurableFirmata's
    /// "Unhandled sysex command" for a feature it was built without.
    #[error("the firmware refused {request}: \"{message}\"")]
    Refused {
        /// What was asked.
        request: String,
        /// The firmware's words.
        message: String,
    },
    /// The I2C device did not answer: fewer bytes than asked came back ("I2C: Too few bytes
    /// received"). Firmata boards do not report a NACK on a write (StandardFirmata 2.5.9 drops
    /// `Wire.endTransmission`'s status), so only reads can tell.
    #[error("I2C device {address:#04x}: no answer (NACK: {got} of {asked} bytes came back)")]
    I2cNack {
        /// The 7-bit address.
        address: u8,
        /// Bytes asked for.
        asked: usize,
        /// Bytes the board returned.
        got: usize,
    },
    /// An I2C transfer Firmata cannot carry in one request; nothing was sent.
    #[error("I2C {what}: {len} bytes, more than the {max} one Firmata request carries")]
    I2cTooLong {
        /// "read" or "write".
        what: &'static str,
        /// Bytes asked for.
        len: usize,
        /// The most one request carries.
        max: usize,
    },
    /// An I2C address or transaction shape Firmata cannot express; nothing was sent.
    #[error("I2C: {0}")]
    I2cUnsupported(&'static str),
    /// A value outside what the message can carry; nothing was sent.
    #[error("{what} = {value} is outside {range}")]
    OutOfRange {
        /// What was out of range.
        what: &'static str,
        /// The value.
        value: String,
        /// The values accepted.
        range: &'static str,
    },
    /// The board is gone: the port hung up (unplugged, or the simulator ended).
    #[error("the port hung up (board disconnected)")]
    Disconnected,
    /// The serial port failed.
    #[error("serial port: {0}")]
    Io(#[from] std::io::Error),
}

fn seen(frame_errors: u64) -> String {
    if frame_errors == 0 {
        String::new()
    } else {
        format!(" ({frame_errors} bytes or messages did not frame as Firmata meanwhile)")
    }
}

/// An error talking to the board on `port`.
///
/// ```
/// use firmata_host::{Error, ErrorKind};
/// let e = Error::new("/dev/ttyACM0", ErrorKind::Disconnected);
/// assert_eq!(e.to_string(), "board on /dev/ttyACM0: the port hung up (board disconnected)");
/// ```
#[derive(Debug, thiserror::Error)]
#[error("board on {port}: {kind}")]
pub struct Error {
    /// The board's port.
    pub port: String,
    /// What failed.
    #[source]
    pub kind: ErrorKind,
}

impl Error {
    /// An error of the board on `port`.
    pub fn new(port: impl Into<String>, kind: ErrorKind) -> Error {
        Error {
            port: port.into(),
            kind,
        }
    }
}

/// embedded-hal's kinds: a short read is a NACK; the rest are bus or other errors.
impl embedded_hal::i2c::Error for Error {
    fn kind(&self) -> embedded_hal::i2c::ErrorKind {
        use embedded_hal::i2c::{ErrorKind as K, NoAcknowledgeSource};
        match self.kind {
            ErrorKind::I2cNack { .. } => K::NoAcknowledge(NoAcknowledgeSource::Unknown),
            ErrorKind::Garbled(_) | ErrorKind::Disconnected | ErrorKind::Io(_) => K::Bus,
            _ => K::Other,
        }
    }
}
