//! The servo side's typed errors: every way a Dynamixel exchange can fail.

use hand_traits::Faults;

use crate::control_table::hardware_error;

/// The instruction error a status packet reports in its error byte (Protocol 2.0, bits 0–6).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum InstructionError {
    /// 0x01: the instruction failed.
    ResultFail,
    /// 0x02: undefined instruction, or ACTION without a registered instruction.
    Instruction,
    /// 0x03: the servo saw a CRC mismatch in our packet.
    Crc,
    /// 0x04: the value is outside the register's range.
    DataRange,
    /// 0x05: the data is shorter than the register.
    DataLength,
    /// 0x06: the value is outside a limit set by another register (e.g. Goal PWM > PWM Limit).
    DataLimit,
    /// 0x07: read-only / undefined address, or EEPROM written while torque is on.
    Access,
    /// Any other code.
    Other(u8),
}

impl InstructionError {
    /// The error from the low 7 bits of a status packet's error byte (`None` when zero).
    ///
    /// ```
    /// use hand_control::InstructionError;
    /// assert_eq!(InstructionError::from_code(0x86), Some(InstructionError::DataLimit));
    /// assert_eq!(InstructionError::from_code(0x80), None); // alert bit only
    /// ```
    pub fn from_code(byte: u8) -> Option<Self> {
        Some(match byte & 0x7F {
            0 => return None,
            1 => Self::ResultFail,
            2 => Self::Instruction,
            3 => Self::Crc,
            4 => Self::DataRange,
            5 => Self::DataLength,
            6 => Self::DataLimit,
            7 => Self::Access,
            n => Self::Other(n),
        })
    }

    /// The code on the wire.
    pub fn code(self) -> u8 {
        match self {
            Self::ResultFail => 1,
            Self::Instruction => 2,
            Self::Crc => 3,
            Self::DataRange => 4,
            Self::DataLength => 5,
            Self::DataLimit => 6,
            Self::Access => 7,
            Self::Other(n) => n & 0x7F,
        }
    }
}

/// What the servo said, in the e-Manual's words (Protocol 2.0, status packet error field).
///
/// ```
/// use hand_control::InstructionError;
/// assert_eq!(InstructionError::DataLimit.to_string(), "data limit error (0x06: a value over a limit register)");
/// ```
impl core::fmt::Display for InstructionError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        let what = match self {
            Self::ResultFail => "result fail (0x01: the instruction failed)",
            Self::Instruction => "instruction error (0x02: undefined, or ACTION without REG_WRITE)",
            Self::Crc => "CRC error (0x03: the servo saw a corrupted packet)",
            Self::DataRange => "data range error (0x04: a value out of the register's range)",
            Self::DataLength => "data length error (0x05: data shorter than the register)",
            Self::DataLimit => "data limit error (0x06: a value over a limit register)",
            Self::Access => {
                "access error (0x07: read-only address, or EEPROM written with torque on)"
            }
            Self::Other(n) => return write!(f, "error code {n:#04x}"),
        };
        f.write_str(what)
    }
}

/// Hardware Error Status bits mapped onto the actuator-independent [`Faults`].
///
/// ```
/// use hand_control::faults_from_hardware_error;
/// use hand_traits::Faults;
/// assert_eq!(faults_from_hardware_error(0x20), Faults::OVERLOAD);
/// assert!(faults_from_hardware_error(0x05).contains(Faults::OVERHEAT.union(Faults::VOLTAGE)));
/// ```
pub fn faults_from_hardware_error(bits: u8) -> Faults {
    [
        (hardware_error::INPUT_VOLTAGE, Faults::VOLTAGE),
        (hardware_error::OVERHEATING, Faults::OVERHEAT),
        (hardware_error::MOTOR_ENCODER, Faults::ENCODER),
        (hardware_error::ELECTRICAL_SHOCK, Faults::ELECTRICAL),
        (hardware_error::OVERLOAD, Faults::OVERLOAD),
    ]
    .into_iter()
    .filter(|(bit, _)| bits & bit != 0)
    .fold(Faults::NONE, |acc, (_, f)| acc.union(f))
}

/// Who an exchange asked, as an error names it: `servo 3`, or `the bus` for a broadcast
/// (the `Option`'s own Debug, `servo Some(3)`, is not for users).
struct Asked(Option<u8>);

impl core::fmt::Display for Asked {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self.0 {
            Some(id) => write!(f, "servo {id}"),
            None => f.write_str("the bus"),
        }
    }
}

/// What can go wrong talking to Dynamixel servos.
///
/// Each text names the servo by its ID, or the bus for a broadcast exchange:
///
/// ```
/// use hand_control::Error;
/// assert_eq!(Error::Timeout { id: Some(1) }.to_string(), "servo 1: no answer (timeout)");
/// assert_eq!(Error::Timeout { id: None }.to_string(), "the bus: no answer (timeout)");
/// ```
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// No status packet arrived before the deadline.
    #[error("{}: no answer (timeout)", Asked(*.id))]
    Timeout {
        /// The servo asked (`None` for a broadcast exchange).
        id: Option<u8>,
    },
    /// A status packet arrived with a wrong CRC-16.
    #[error(
        "{}: status packet CRC mismatch (sent {message:#06x}, computed {computed:#06x})",
        Asked(*.id)
    )]
    Crc {
        /// The servo asked.
        id: Option<u8>,
        /// CRC in the packet.
        message: u16,
        /// CRC of the bytes received.
        computed: u16,
    },
    /// The servo refused the instruction (status packet error byte).
    #[error("servo {id}: instruction refused: {error}")]
    Status {
        /// The servo.
        id: u8,
        /// The error it reported.
        error: InstructionError,
    },
    /// The servo's Hardware Error Status is not zero (alert bit set).
    #[error("servo {id}: hardware error status {bits:#04x} ({faults})")]
    Hardware {
        /// The servo.
        id: u8,
        /// The raw Hardware Error Status bits.
        bits: u8,
        /// The bits as actuator faults.
        faults: Faults,
    },
    /// A command value outside what the model accepts; nothing was sent.
    #[error("{what} = {value} is outside {min} ..= {max}")]
    OutOfRange {
        /// What was out of range.
        what: &'static str,
        /// The rejected value.
        value: f64,
        /// Lowest accepted.
        min: f64,
        /// Highest accepted.
        max: f64,
    },
    /// A servo answered PING with a model number no control table here describes.
    #[error("servo {id}: unknown model number {model_number}")]
    UnknownModel {
        /// The servo.
        id: u8,
        /// Its model number.
        model_number: u16,
    },
    /// The servos of one hand are of different models (one sync read needs one layout).
    #[error("servo {id} is a {found}, the hand's first servo a {expected}")]
    MixedModels {
        /// The odd servo.
        id: u8,
        /// The first servo's model.
        expected: &'static str,
        /// This servo's model.
        found: &'static str,
    },
    /// A hand needs at least one servo.
    #[error("a servo hand needs at least one servo")]
    NoServos,
    /// A malformed or unexpected status packet (wrong ID, instruction or length).
    #[error("{}: invalid status packet: {detail}", Asked(*.id))]
    Protocol {
        /// The servo asked.
        id: Option<u8>,
        /// What was wrong.
        detail: String,
    },
    /// An instruction longer than the bus's write buffer; nothing was sent.
    #[error(
        "instruction of {required} bytes does not fit the {capacity}-byte write buffer; nothing was sent"
    )]
    InstructionTooLong {
        /// Bytes the instruction needs.
        required: usize,
        /// Bytes the buffer holds.
        capacity: usize,
    },
    /// The serial port failed.
    #[error("serial port: {0}")]
    Io(#[from] std::io::Error),
}

impl Error {
    /// Converts a `dynamixel2` write error.
    pub(crate) fn from_write(e: dynamixel2::WriteError) -> Self {
        use dynamixel2::WriteError as W;
        match e {
            W::DiscardBuffer(io) | W::Write(io) => Error::Io(io),
            W::BufferTooSmall(b) => Error::InstructionTooLong {
                required: b.required_size,
                capacity: b.total_size,
            },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::Error;

    /// A write that cannot fit is said as such, not as a bad status packet.
    #[test]
    fn an_instruction_too_long_for_the_buffer_is_not_a_protocol_error() {
        let e = Error::from_write(dynamixel2::WriteError::BufferTooSmall(
            dynamixel2::BufferTooSmallError {
                required_size: 300,
                total_size: 256,
            },
        ));
        assert_eq!(
            e.to_string(),
            "instruction of 300 bytes does not fit the 256-byte write buffer; nothing was sent"
        );
    }

    /// The texts a user reads name the servo by its number, never as `Some(1)`.
    #[test]
    fn errors_name_the_servo_by_its_id_or_the_bus() {
        assert_eq!(
            Error::Timeout { id: Some(1) }.to_string(),
            "servo 1: no answer (timeout)"
        );
        assert_eq!(
            Error::Timeout { id: None }.to_string(),
            "the bus: no answer (timeout)"
        );
        assert_eq!(
            Error::Crc {
                id: Some(7),
                message: 0x1234,
                computed: 0xabcd
            }
            .to_string(),
            "servo 7: status packet CRC mismatch (sent 0x1234, computed 0xabcd)"
        );
        assert_eq!(
            Error::Protocol {
                id: Some(2),
                detail: "wrong ID 3".into()
            }
            .to_string(),
            "servo 2: invalid status packet: wrong ID 3"
        );
        assert_eq!(
            Error::Protocol {
                id: None,
                detail: "short".into()
            }
            .to_string(),
            "the bus: invalid status packet: short"
        );
    }
}
