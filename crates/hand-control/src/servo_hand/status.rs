//! Instruction → status exchanges, with this crate's status-packet parser and a reply timeout
//! the caller chooses.
//!
//! Instructions go out through `dynamixel2` (`Bus::write_instruction`: header, stuffing, CRC).
//! Replies are read here, for two reasons:
//! - `dynamixel2` 0.9.1 removes byte stuffing with a matcher that restarts from zero on a
//!   mismatch, so a status packet whose data holds `FF FF FF FD` (e.g. Present Load −1 followed
//!   by a negative Present Velocity) keeps its stuffing byte and fails with
//!   `InvalidParameterCount`; [`crate::protocol`] implements the e-Manual rule ("FF FF FD"
//!   anywhere in the body gets one extra FD);
//! - its reply timeout is fixed (34 ms + wire time, as the ROBOTIS SDK), which a simulated
//!   servo on a loaded machine can miss; [`ServoHand::set_reply_latency`](super::ServoHand::set_reply_latency)
//!   sets it here.
//!
//! The driver's own instruction parameters are non-negative goals and addresses, which never
//! contain the pattern `dynamixel2` would stuff wrongly.

use std::time::{Duration, Instant};

use dynamixel2::Bus;
use dynamixel2::instructions::instruction_id;
use dynamixel2::serial2::SerialPort;

use crate::InstructionError;
use crate::error::Error;
use crate::protocol::{FrameError, Packet, Parser};

/// One servo's status packet.
pub(super) struct Answer {
    pub(super) id: u8,
    pub(super) alert: bool,
    pub(super) data: Vec<u8>,
}

/// The bus plus what reading replies needs.
#[derive(Debug)]
pub(super) struct Link {
    /// `dynamixel2`'s bus: sends instructions.
    pub(super) bus: Bus<Vec<u8>, Vec<u8>>,
    /// A clone of the bus's port, so its read timeout can follow each reply's deadline.
    reader: SerialPort,
    /// How long the replies to one instruction may take beyond their wire time.
    pub(super) latency: Duration,
}

impl Link {
    /// Wraps `bus`.
    pub(super) fn new(bus: Bus<Vec<u8>, Vec<u8>>, latency: Duration) -> std::io::Result<Self> {
        let reader = bus.serial_port().try_clone()?;
        Ok(Self {
            bus,
            reader,
            latency,
        })
    }

    /// Sends one instruction to `packet_id` and collects the status packets of `expect` (in that
    /// order), each with `count` data bytes. Answers are matched by ID, so one missing status packet
    /// is that servo's [`Error::Timeout`] and does not shift the others. All answers may take
    /// `latency` plus their wire time.
    ///
    /// # Errors
    /// The first failure in `expect` order, after every answer (or its timeout) has been consumed;
    /// a status packet from a servo not in `expect` is an [`Error::Protocol`].
    pub(super) fn exchange(
        &mut self,
        packet_id: u8,
        instruction: u8,
        params: &[u8],
        expect: &[u8],
        count: u16,
    ) -> Result<Vec<Answer>, Error> {
        self.bus
            .write_instruction(packet_id, instruction, params.len(), |b| {
                b.copy_from_slice(params)
            })
            .map_err(Error::from_write)?;
        if expect.is_empty() {
            return Ok(Vec::new());
        }
        let baud = u64::from(self.bus.baud_rate().max(1));
        // Servos answer back to back: one latency allowance, then every answer's wire time.
        let wire = Duration::from_nanos((11 + u64::from(count)) * 10 * 1_000_000_000 / baud);
        let deadline = Instant::now() + self.latency + wire * expect.len() as u32;
        let mut parser = Parser::default();
        let mut buf = [0u8; 512];
        let mut results: Vec<Option<Result<Answer, Error>>> = expect.iter().map(|_| None).collect();
        let mut stray = None;
        loop {
            while let Some(frame) = parser.next_packet() {
                let (from, result) = match frame {
                    Ok(p) => (p.id, check(count, p)),
                    Err(FrameError::Crc {
                        id, sent, computed, ..
                    }) => (
                        id,
                        Err(Error::Crc {
                            id: Some(id),
                            message: sent,
                            computed,
                        }),
                    ),
                    Err(FrameError::BadLength) => continue,
                };
                // A corrupted ID byte: charge the error to the first servo still waiting.
                let slot = expect
                    .iter()
                    .zip(&results)
                    .position(|(&i, r)| i == from && r.is_none())
                    .or_else(|| results.iter().position(Option::is_none));
                match slot {
                    Some(k) => results[k] = Some(result),
                    None => {
                        stray.get_or_insert(Error::Protocol {
                            id: Some(from),
                            detail: "a status packet nobody asked for".into(),
                        });
                    }
                }
            }
            if results.iter().all(Option::is_some) || Instant::now() >= deadline {
                break;
            }
            // A clone of the bus's port, so its read timeout can follow the deadline.
            let left = deadline.saturating_duration_since(Instant::now());
            self.reader
                .set_read_timeout(left.max(Duration::from_micros(100)))?;
            match self.reader.read(&mut buf) {
                Ok(n) => parser.push(&buf[..n]),
                Err(e) if e.kind() == std::io::ErrorKind::TimedOut => {}
                Err(e) => return Err(Error::Io(e)),
            }
        }
        let mut out = Vec::with_capacity(expect.len());
        for (&id, r) in expect.iter().zip(results) {
            out.push(r.unwrap_or(Err(Error::Timeout { id: Some(id) }))?);
        }
        match stray {
            Some(e) => Err(e),
            None => Ok(out),
        }
    }
}

/// Checks a status packet: a status, no error code, `count` data bytes.
fn check(count: u16, p: Packet) -> Result<Answer, Error> {
    let id = p.id;
    let bad = |detail: String| Error::Protocol {
        id: Some(id),
        detail,
    };
    if p.instruction != instruction_id::STATUS {
        return Err(bad(format!(
            "instruction {:#04x}, not a status",
            p.instruction
        )));
    }
    let (&err, data) = p
        .params
        .split_first()
        .ok_or_else(|| bad("no error byte".into()))?;
    if let Some(error) = InstructionError::from_code(err) {
        return Err(Error::Status { id, error });
    }
    if data.len() != usize::from(count) {
        return Err(bad(format!("{} data bytes, expected {count}", data.len())));
    }
    Ok(Answer {
        id,
        alert: err & 0x80 != 0,
        data: data.to_vec(),
    })
}
