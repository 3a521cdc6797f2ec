//! The board → host byte stream as messages, one byte at a time, without allocating.
//!
//! Framing follows protocol.md 2.6.0 ("Message Types", "Sysex Message Format"): a byte with
//! bit 7 set starts a message; analog (`E0|ch`), digital (`90|port`) and version (`F9`)
//! messages take two 7-bit data bytes; a sysex runs from `F0` to `F7` and every byte between
//! has bit 7 clear. Reports arrive whenever the board sends them, so they interleave freely
//! with the reply a request waits for: the parser yields each as it completes.
//!
//! What does not frame is a [`FrameError`], and the parser goes on with the next byte: a status
//! byte inside a sysex ends it as [`FrameError::TruncatedSysex`] and starts its own message;
//! data bytes outside a message are [`FrameError::StrayData`] (what a board at another baud
//! rate mostly produces); status bytes a board does not send are
//! [`FrameError::UnknownCommand`]. No byte sequence makes it panic.
//!
//! ```
//! use firmata_host::parser::{Event, Parser};
//! let mut parser = Parser::new();
//! let mut seen = Vec::new();
//! // An analog report arrives before the firmware query's reply: both are delivered.
//! for &b in &[0xE0, 0x7F, 0x07, 0xF0, 0x79, 0x02, 0x05, 0x53, 0x00, 0xF7] {
//!     if let Some(Ok(event)) = parser.push(b) {
//!         seen.push(format!("{event:?}"));
//!     }
//! }
//! assert_eq!(seen[0], "Analog { channel: 0, value: 1023 }");
//! assert_eq!(seen[1], "Firmware { major: 2, minor: 5, name: [83, 0] }");
//! ```

use crate::protocol::{self, from_7bit_pair};

/// Bytes of one sysex a host keeps (ID and payload): a Mega 2560's capability response under
/// StandardFirmata 2.5.9 is 70 pins × at most 13 bytes, about 900.
pub const SYSEX_CAPACITY: usize = 2048;

/// A message from the board, borrowing the parser's buffer until the next byte is pushed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum Event<'a> {
    /// Analog message: a channel's 14-bit value (10-bit counts on AVR boards).
    Analog {
        /// Analog channel 0–15 (A0 = 0).
        channel: u8,
        /// The value.
        value: u16,
    },
    /// Digital message: a port's pin levels (bit k = pin 8·port + k).
    Digital {
        /// Port 0–15.
        port: u8,
        /// Levels of its 8 pins.
        mask: u8,
    },
    /// Protocol version report.
    Version {
        /// Major version.
        major: u8,
        /// Minor version.
        minor: u8,
    },
    /// Firmware name and version report.
    Firmware {
        /// Firmware major version.
        major: u8,
        /// Firmware minor version.
        minor: u8,
        /// The name as 14-bit characters (decode with [`protocol::pairs`]).
        name: &'a [u8],
    },
    /// Capability response: per pin, (mode, resolution) pairs, each pin closed by 0x7F.
    Capabilities(&'a [u8]),
    /// Analog mapping response: per pin, its analog channel or 127.
    AnalogMapping(&'a [u8]),
    /// Pin state response.
    PinState {
        /// The pin.
        pin: u8,
        /// Its mode code.
        mode: u8,
        /// Its state (7 bits per byte, up to 3 bytes).
        state: u32,
    },
    /// I2C reply: the data as 7-bit pairs. A reply whose address does not fit 7 bits is
    /// [`FrameError::Malformed`]: it answers no request of this host.
    I2cReply {
        /// The 7-bit address read.
        address: u8,
        /// The register read (0 when the request named none).
        register: u16,
        /// The bytes read as 7-bit pairs (decode with [`protocol::pairs`]).
        data: &'a [u8],
    },
    /// A string (14-bit characters): boards report errors with it.
    Text(&'a [u8]),
    /// A stepper's position, on request.
    StepperPosition {
        /// Device 0–9.
        device: u8,
        /// Steps from zero.
        position: i32,
    },
    /// A stepper finished its move (or was stopped), at this position.
    StepperMoveComplete {
        /// Device 0–9.
        device: u8,
        /// Steps from zero.
        position: i32,
    },
    /// A multi-stepper group finished.
    MultiStepperComplete {
        /// Group 0–4.
        group: u8,
    },
    /// A well-framed sysex this crate does not decode (an optional feature's report).
    Sysex {
        /// Its ID.
        id: u8,
        /// Its payload.
        payload: &'a [u8],
    },
}

/// A byte sequence that does not frame as a Firmata message.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum FrameError {
    /// A sysex cut short by a status byte before its `F7` (bytes lost on the line).
    TruncatedSysex {
        /// Its ID (`None` if cut before the ID).
        id: Option<u8>,
        /// Bytes received after `F0`, those beyond [`SYSEX_CAPACITY`] included.
        len: usize,
    },
    /// A two-byte message cut short by a status byte.
    TruncatedMessage {
        /// Its command byte.
        command: u8,
    },
    /// A data byte outside any message.
    StrayData(u8),
    /// A status byte no Firmata board sends.
    UnknownCommand(u8),
    /// A sysex longer than [`SYSEX_CAPACITY`]: its tail was dropped, so it is not delivered.
    SysexOverflow {
        /// Its ID.
        id: u8,
    },
    /// A well-framed sysex whose payload does not fit its ID's layout.
    Malformed {
        /// Its ID.
        id: u8,
        /// Payload length.
        len: usize,
    },
}

impl core::fmt::Display for FrameError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            FrameError::TruncatedSysex { id: Some(id), len } => {
                write!(f, "truncated sysex {id:#04x} ({len} bytes, no END_SYSEX)")
            }
            FrameError::TruncatedSysex { id: None, len: _ } => f.write_str("empty truncated sysex"),
            FrameError::TruncatedMessage { command } => {
                write!(f, "truncated message {command:#04x}")
            }
            FrameError::StrayData(b) => write!(f, "stray data byte {b:#04x}"),
            FrameError::UnknownCommand(b) => write!(f, "unknown command byte {b:#04x}"),
            FrameError::SysexOverflow { id } => {
                write!(f, "sysex {id:#04x} longer than {SYSEX_CAPACITY} bytes")
            }
            FrameError::Malformed { id, len } => {
                write!(f, "malformed sysex {id:#04x} ({len}-byte payload)")
            }
        }
    }
}

impl std::error::Error for FrameError {}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum State {
    Idle,
    /// A two-data-byte message (analog, digital, version) with `got` bytes in.
    Two {
        command: u8,
        got: u8,
    },
    Sysex,
}

/// The incremental parser: push bytes, get messages. Its buffer is allocated once.
#[derive(Debug, Clone)]
pub struct Parser {
    state: State,
    data: [u8; 2],
    buf: Box<[u8; SYSEX_CAPACITY]>,
    /// Bytes of the open sysex received after `F0`; the first [`SYSEX_CAPACITY`] are in `buf`.
    len: usize,
}

impl Default for Parser {
    fn default() -> Self {
        Parser::new()
    }
}

impl Parser {
    /// A parser between messages.
    pub fn new() -> Parser {
        Parser {
            state: State::Idle,
            data: [0; 2],
            buf: Box::new([0; SYSEX_CAPACITY]),
            len: 0,
        }
    }

    /// Takes one byte; returns the message or framing error it completes, if any.
    ///
    /// A status byte that cuts a message short returns that message's error; the new message
    /// it starts is parsed as usual.
    pub fn push(&mut self, byte: u8) -> Option<Result<Event<'_>, FrameError>> {
        if byte & 0x80 == 0 {
            return self.data_byte(byte);
        }
        if self.state == State::Sysex && byte == protocol::END_SYSEX {
            self.state = State::Idle;
            return Some(self.finish_sysex());
        }
        let cut = match self.state {
            State::Idle => None,
            State::Two { command, .. } => Some(FrameError::TruncatedMessage { command }),
            State::Sysex => Some(FrameError::TruncatedSysex {
                id: (self.len > 0).then(|| self.buf[0]),
                len: self.len,
            }),
        };
        self.state = State::Idle;
        let started = match byte & 0xF0 {
            protocol::ANALOG_MESSAGE | protocol::DIGITAL_MESSAGE => {
                self.state = State::Two {
                    command: byte,
                    got: 0,
                };
                None
            }
            _ => match byte {
                protocol::REPORT_VERSION => {
                    self.state = State::Two {
                        command: byte,
                        got: 0,
                    };
                    None
                }
                protocol::START_SYSEX => {
                    self.state = State::Sysex;
                    self.len = 0;
                    None
                }
                other => Some(FrameError::UnknownCommand(other)),
            },
        };
        // A cut message is the older news; the unknown command (rare) is reported on its own
        // when nothing was cut.
        cut.or(started).map(Err)
    }

    fn data_byte(&mut self, byte: u8) -> Option<Result<Event<'_>, FrameError>> {
        match self.state {
            State::Idle => Some(Err(FrameError::StrayData(byte))),
            State::Two { command, got } => {
                self.data[usize::from(got)] = byte;
                if got == 0 {
                    self.state = State::Two { command, got: 1 };
                    return None;
                }
                self.state = State::Idle;
                let value = from_7bit_pair(self.data[0], self.data[1]);
                let channel = command & 0x0F;
                Some(Ok(match command & 0xF0 {
                    protocol::ANALOG_MESSAGE => Event::Analog { channel, value },
                    protocol::DIGITAL_MESSAGE => Event::Digital {
                        port: channel,
                        mask: (value & 0xFF) as u8,
                    },
                    _ => Event::Version {
                        major: self.data[0],
                        minor: self.data[1],
                    },
                }))
            }
            State::Sysex => {
                if let Some(slot) = self.buf.get_mut(self.len) {
                    *slot = byte;
                }
                self.len = self.len.saturating_add(1);
                None
            }
        }
    }

    fn finish_sysex(&self) -> Result<Event<'_>, FrameError> {
        let kept = &self.buf[..self.len.min(SYSEX_CAPACITY)];
        let Some((&id, payload)) = kept.split_first() else {
            return Err(FrameError::TruncatedSysex { id: None, len: 0 });
        };
        if self.len > SYSEX_CAPACITY {
            return Err(FrameError::SysexOverflow { id });
        }
        decode_sysex(id, payload)
    }
}

/// Decodes one complete sysex (without `F0` / `F7`): the ID and its payload.
pub fn decode_sysex(id: u8, payload: &[u8]) -> Result<Event<'_>, FrameError> {
    let malformed = FrameError::Malformed {
        id,
        len: payload.len(),
    };
    Ok(match id {
        protocol::REPORT_FIRMWARE => match payload {
            [major, minor, name @ ..] => Event::Firmware {
                major: *major,
                minor: *minor,
                name,
            },
            _ => return Err(malformed),
        },
        protocol::CAPABILITY_RESPONSE => Event::Capabilities(payload),
        protocol::ANALOG_MAPPING_RESPONSE => Event::AnalogMapping(payload),
        protocol::PIN_STATE_RESPONSE => match payload {
            [pin, mode, state @ ..] if !state.is_empty() && state.len() <= 3 => Event::PinState {
                pin: *pin,
                mode: *mode,
                state: state
                    .iter()
                    .enumerate()
                    .fold(0, |acc, (k, b)| acc | (u32::from(*b) << (7 * k))),
            },
            _ => return Err(malformed),
        },
        // The address's second byte is 0: the host asks 7-bit addresses only, and a wider one
        // would alias a 7-bit one if its upper bits were dropped.
        protocol::I2C_REPLY => match payload {
            [al, am, rl, rm, data @ ..] if am & 0x7F == 0 && data.len() % 2 == 0 => {
                Event::I2cReply {
                    address: al & 0x7F,
                    register: from_7bit_pair(*rl, *rm),
                    data,
                }
            }
            _ => return Err(malformed),
        },
        protocol::STRING_DATA => Event::Text(payload),
        protocol::ACCELSTEPPER_DATA => match payload {
            [command, device, a, b, c, d, e]
                if *command == protocol::ACCELSTEPPER_REPORT_POSITION
                    || *command == protocol::ACCELSTEPPER_MOVE_COMPLETE =>
            {
                let position = protocol::decode_stepper_i32([*a, *b, *c, *d, *e]);
                if *command == protocol::ACCELSTEPPER_MOVE_COMPLETE {
                    Event::StepperMoveComplete {
                        device: *device,
                        position,
                    }
                } else {
                    Event::StepperPosition {
                        device: *device,
                        position,
                    }
                }
            }
            [command, group] if *command == protocol::MULTISTEPPER_MOVE_COMPLETE => {
                Event::MultiStepperComplete { group: *group }
            }
            _ => return Err(malformed),
        },
        _ => Event::Sysex { id, payload },
    })
}

/// The fuzz entry point: parses `bytes` from a fresh parser and calls `each` with every
/// message or framing error, in order. Pure: no I/O, no allocation beyond the parser's buffer.
///
/// ```
/// let mut events = 0;
/// let mut errors = 0;
/// firmata_host::parser::parse_stream(&[0xF9, 2, 5, 0x42, 0xF0, 0x79], |r| match r {
///     Ok(_) => events += 1,
///     Err(_) => errors += 1,
/// });
/// assert_eq!((events, errors), (1, 1)); // the version; the stray 0x42 (the open sysex is pending)
/// ```
pub fn parse_stream(bytes: &[u8], mut each: impl FnMut(Result<Event<'_>, FrameError>)) {
    let mut parser = Parser::new();
    for &b in bytes {
        if let Some(r) = parser.push(b) {
            each(r);
        }
    }
}
