//! The wire format of a barometric fingertip's microcontroller (Kim et al. 2020, §2: three
//! MS5611 under silicone, read by a Cortex-M3 that estimates force and contact): one
//! checksummed frame per sensor cycle over a UART.
//!
//! - [`Frame`]: what one cycle reports (pressures, force, the Arrival-of-Time cell on the 3 × 3
//!   grid, the contact MLP's cell on the 4 × 6 pad, the grasp torque limit) and its 28 bytes
//!   ([`Frame::encode`], [`Frame::decode`]);
//! - [`FrameReader`]: frames out of a byte stream that may start mid-frame, carry noise or
//!   lose bytes: it resynchronises on the sync bytes and counts what it dropped.
//!
//! `no_std`, no allocation, no dependencies: the MCU encodes with the same code the host
//! decodes with.
//!
//! ```
//! use fingertip_link::{Frame, FrameReader, LEN};
//!
//! let sent = Frame {
//!     seq: 7,
//!     t_us: 1_000_000,
//!     pressure_pa: [101_325, 101_410, 101_300],
//!     tared: true,
//!     in_contact: true,
//!     force_gf: Some(49.5),
//!     grid_cell: Some(4),
//!     pad_cell: Some(14),
//!     torque_raw: 300,
//!     ..Frame::default()
//! };
//! let bytes = sent.encode();
//! assert_eq!(bytes.len(), LEN);
//!
//! // The host joins the UART mid-frame: the reader skips to the next sync and checks the sum.
//! let mut reader = FrameReader::new();
//! let mut got = None;
//! for &b in bytes[20..].iter().chain(&bytes) {
//!     if let Some(frame) = reader.push(b) {
//!         got = Some(frame);
//!     }
//! }
//! assert_eq!(got, Some(Ok(sent)));
//! assert_eq!(reader.dropped_bytes(), 8);
//! ```

#![no_std]
#![forbid(unsafe_code)]

mod frame;
mod reader;

pub use frame::{
    BAUD, FAULT, Frame, FrameError, GRID_CELLS, IN_CONTACT, LEN, NONE_U8, NONE_U16, PAD_CELLS,
    SYNC, TARED, fletcher16,
};
pub use reader::FrameReader;
