//! Arduino boards over Firmata, from the host.
//!
//! [`Board`] opens a board running StandardFirmata or ConfigurableFirmata 2.x on a serial port
//! (`serial2`, 57 600 baud by default), waits through the reset an Arduino makes when its port
//! opens (for the version report, with a timeout, not a fixed sleep), and keeps the latest of
//! everything the board reports — analog inputs in counts and volts, digital ports, I2C
//! replies, stepper positions — while requests wait for their replies among those reports.
//!
//! - [`protocol`]: the wire format, each rule cited to the Firmata document or firmware
//!   source it comes from, with encoders for both directions;
//! - [`parser`]: the board → host byte stream as messages, one byte at a time, no allocation;
//!   [`parser::parse_stream`] is the pure entry point for fuzzing;
//! - [`Board`] implements embedded-hal 1.0 [`I2c`](embedded_hal::i2c::I2c) (see [`i2c`] for
//!   how a transaction maps onto Firmata requests and what Firmata cannot carry), so a chip
//!   driver runs unchanged through the board; [`StdDelay`] is the delay such drivers take;
//! - AccelStepperFirmata (ConfigurableFirmata): [`Board::stepper_config`], moves, speed,
//!   acceleration, stop, position and move-complete reports;
//! - [`Error`] names the board's port and what failed ([`ErrorKind`]): a timeout, a garbled
//!   or truncated reply, a refusal by the firmware, an I2C NACK, bytes that are not Firmata
//!   (another sketch, another baud rate), a board that vanished.
//!
//! The README follows (its examples are this crate's doctests).
//!
#![doc = include_str!("../README.md")]
#![deny(unsafe_code)]

mod board;
mod delay;
mod error;
pub mod i2c;
pub mod parser;
pub mod protocol;

pub use board::{
    AnalogReading, Board, Firmware, LinkStats, Options, PinCapabilities, StepperConfig,
    StepperInterface, parse_capabilities,
};
pub use delay::StdDelay;
pub use error::{Error, ErrorKind};
pub use protocol::PinMode;
