//! Instruction → status exchanges, with this crate's status-packet parser and a reply timeout
//! the caller chooses.
//!
//! Instructions go out through `dynamixel2` (`Bus::write_instruction`: header, stuffing, CRC).
//! Replies are read here, for two reasons:
//! - `dynamixel2` 0.9.1 removes byte stuffing with a matcher that restarts from zero on a
//!   mismatch, so a status packet whose data holds `FF FF FF FD` (e.g. Present Load −1 followed
//!   by a negative Present Velocity) keeps its stuffing byte and fails with
//!   `InvalidParameterCount`; this module applies the e-Manual rule ("FF FF FD" anywhere in
//!   the body gets one extra FD), as [`crate::protocol`] does;
//! - its reply timeout is fixed (34 ms + wire time, as the ROBOTIS SDK), which a simulated
//!   servo on a loaded machine can miss; [`ServoHand::set_reply_latency`](super::ServoHand::set_reply_latency)
//!   sets it here.
//!
//! The driver's own instruction parameters are non-negative goals and addresses, which never
//! contain the pattern `dynamixel2` would stuff wrongly.
//!
//! Replies are framed in place ([`crate::protocol`]'s one framing, without the per-packet
//! `Vec` of its [`Parser`](crate::protocol::Parser)) into buffers the [`Link`] keeps, so a
//! steady exchange allocates nothing.

use std::time::{Duration, Instant};

use dynamixel2::Bus;
use dynamixel2::instructions::instruction_id;
use dynamixel2::serial2::SerialPort;

use crate::InstructionError;
use crate::error::Error;
use crate::protocol::{FrameError, Framed, MAX_LEN, next_frame};

/// Bytes one `read` of the port takes at most.
const READ_CHUNK: usize = 512;
/// Received bytes the link holds without growing: one whole frame of the longest length the
/// framing accepts, plus a read's worth behind it.
const RX_CAPACITY: usize = 7 + MAX_LEN + READ_CHUNK;

/// One servo's status packet, borrowed from the link until its next exchange.
#[derive(Debug, Clone, Copy)]
pub(super) struct Answer<'a> {
    pub(super) id: u8,
    pub(super) alert: bool,
    pub(super) data: &'a [u8],
}

/// Where one expected status packet stands during an exchange.
#[derive(Debug)]
enum Slot {
    /// Nothing yet.
    Waiting,
    /// A good status packet (its data is in [`Link::data`]).
    Answered { id: u8, alert: bool },
    /// A bad one.
    Failed(Error),
}

/// The bus plus what reading replies needs.
///
/// Every buffer an exchange uses lives here and keeps its capacity, so an exchange allocates
/// nothing once the buffers have reached the size of the largest exchange (the constructor
/// reserves for the hand's sync read): no frame `Vec`s, no answer `Vec`s. Only failures
/// allocate (an [`Error::Protocol`] carries a `String`).
#[derive(Debug)]
pub(super) struct Link {
    /// `dynamixel2`'s bus: sends instructions.
    pub(super) bus: Bus<Vec<u8>, Vec<u8>>,
    /// A clone of the bus's port, so its read timeout can follow each reply's deadline.
    reader: SerialPort,
    /// How long the replies to one instruction may take beyond their wire time.
    pub(super) latency: Duration,
    /// Bytes received and not framed yet.
    rx: Vec<u8>,
    /// One per expected status packet of the last exchange, in `expect` order.
    slots: Vec<Slot>,
    /// The answers' data, `count` bytes per slot, in slot order.
    data: Vec<u8>,
    /// Data bytes per answer of the last exchange.
    count: usize,
    /// Instruction packets written and status packets framed (bad CRC included) so far.
    pub(super) packets: super::PacketCounts,
}

impl Link {
    /// Wraps `bus`.
    pub(super) fn new(bus: Bus<Vec<u8>, Vec<u8>>, latency: Duration) -> std::io::Result<Self> {
        let reader = bus.serial_port().try_clone()?;
        Ok(Self {
            bus,
            reader,
            latency,
            rx: Vec::with_capacity(RX_CAPACITY),
            slots: Vec::new(),
            data: Vec::new(),
            count: 0,
            packets: super::PacketCounts::default(),
        })
    }

    /// Makes room for exchanges of up to `answers` status packets of `count` data bytes each,
    /// so they allocate nothing.
    /// Sends instruction packets framed elsewhere (no answer expected), dropping any stale
    /// input first as `dynamixel2` does before every instruction it writes.
    pub(super) fn send(&mut self, wire: &[u8]) -> std::io::Result<()> {
        let port = self.bus.serial_port();
        port.discard_input_buffer()?;
        port.write_all(wire)
    }

    pub(super) fn reserve(&mut self, answers: usize, count: u16) {
        self.slots.reserve(answers);
        self.data
            .reserve(answers.saturating_mul(usize::from(count)));
    }

    /// The `k`-th answer (in `expect` order) of the last successful exchange.
    pub(super) fn answer(&self, k: usize) -> Option<Answer<'_>> {
        match self.slots.get(k)? {
            &Slot::Answered { id, alert } => Some(Answer {
                id,
                alert,
                data: self
                    .data
                    .get(k * self.count..(k + 1) * self.count)
                    .unwrap_or_default(),
            }),
            _ => None,
        }
    }

    /// Sends one instruction to `packet_id` and collects the status packets of `expect` (in that
    /// order), each with `count` data bytes; read them with [`Link::answer`]. Answers are matched
    /// by ID, so one missing status packet is that servo's [`Error::Timeout`] and does not shift
    /// the others. All answers may take `latency` plus their wire time.
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
    ) -> Result<(), Error> {
        self.slots.clear();
        self.bus
            .write_instruction(packet_id, instruction, params.len(), |b| {
                b.copy_from_slice(params)
            })
            .map_err(Error::from_write)?;
        self.packets.sent += 1;
        if expect.is_empty() {
            return Ok(());
        }
        let n = usize::from(count);
        self.count = n;
        self.slots.extend(expect.iter().map(|_| Slot::Waiting));
        self.data.clear();
        self.data.resize(expect.len() * n, 0);
        // Bytes left from an earlier exchange are stale (the bus discarded the port's too).
        self.rx.clear();
        let baud = u64::from(self.bus.baud_rate().max(1));
        // Servos answer back to back: one latency allowance, then every answer's wire time.
        let wire = Duration::from_nanos((11 + u64::from(count)) * 10 * 1_000_000_000 / baud);
        let deadline = Instant::now() + self.latency + wire * expect.len() as u32;
        let mut buf = [0u8; READ_CHUNK];
        let mut stray = None;
        loop {
            self.packets.received += take_answers(
                &mut self.rx,
                count,
                expect,
                &mut self.slots,
                &mut self.data,
                &mut stray,
            );
            if !self.slots.iter().any(|s| matches!(s, Slot::Waiting)) || Instant::now() >= deadline
            {
                break;
            }
            // A clone of the bus's port, so its read timeout can follow the deadline.
            let left = deadline.saturating_duration_since(Instant::now());
            self.reader
                .set_read_timeout(left.max(Duration::from_micros(100)))?;
            match self.reader.read(&mut buf) {
                Ok(got) => self.rx.extend_from_slice(&buf[..got]),
                // A signal arriving while the read waits (EINTR: the user's Ctrl-C, whose
                // handler ends the run in order) is no fault of the bus: read on.
                Err(e)
                    if matches!(
                        e.kind(),
                        std::io::ErrorKind::TimedOut | std::io::ErrorKind::Interrupted
                    ) => {}
                Err(e) => return Err(Error::Io(e)),
            }
        }
        outcome(&mut self.slots, expect, stray)
    }
}

/// Frames every whole status packet in `rx` into the first waiting slot of its servo in
/// `expect` (or, for a corrupted ID, the first waiting slot), `count` data bytes per slot in
/// `data`; a packet nobody waits for becomes `stray`. Returns the packets framed.
fn take_answers(
    rx: &mut Vec<u8>,
    count: u16,
    expect: &[u8],
    slots: &mut [Slot],
    data: &mut [u8],
    stray: &mut Option<Error>,
) -> u64 {
    let n = usize::from(count);
    let mut framed = 0;
    while let Some(frame) = next_frame(rx) {
        let (from, result, used) = match frame {
            Ok(Framed {
                id,
                instruction,
                params,
                total,
            }) => {
                let body = rx.get(8..8 + params).unwrap_or_default();
                (id, check(count, id, instruction, body), total)
            }
            Err(FrameError::Crc {
                id, sent, computed, ..
            }) => (
                id,
                Err(Error::Crc {
                    id: Some(id),
                    message: sent,
                    computed,
                }),
                0,
            ),
            Err(FrameError::BadLength) => continue,
        };
        framed += 1;
        let slot = expect
            .iter()
            .zip(slots.iter())
            .position(|(&i, s)| i == from && matches!(s, Slot::Waiting))
            .or_else(|| slots.iter().position(|s| matches!(s, Slot::Waiting)));
        match (slot, result) {
            (Some(k), Ok((alert, answer))) => {
                // `check` made `answer` exactly `count` bytes long.
                if let Some(d) = data.get_mut(k * n..(k + 1) * n) {
                    d.copy_from_slice(answer);
                }
                slots[k] = Slot::Answered { id: from, alert };
            }
            (Some(k), Err(e)) => slots[k] = Slot::Failed(e),
            (None, _) => {
                stray.get_or_insert_with(|| Error::Protocol {
                    id: Some(from),
                    detail: "a status packet nobody asked for".into(),
                });
            }
        }
        rx.drain(..used);
    }
    framed
}

/// The exchange's result once reading stopped: the first failure in `expect` order (a slot
/// still waiting is that servo's timeout), else a stray packet's error.
fn outcome(slots: &mut [Slot], expect: &[u8], stray: Option<Error>) -> Result<(), Error> {
    for (slot, &id) in slots.iter_mut().zip(expect) {
        match slot {
            Slot::Answered { .. } => {}
            Slot::Waiting => return Err(Error::Timeout { id: Some(id) }),
            Slot::Failed(_) => {
                if let Slot::Failed(e) = std::mem::replace(slot, Slot::Waiting) {
                    return Err(e);
                }
            }
        }
    }
    match stray {
        Some(e) => Err(e),
        None => Ok(()),
    }
}

/// One servo's answer in [`decode_replies`]: its ID, the alert bit and its data.
pub type DecodedAnswer = (u8, bool, Vec<u8>);

/// What the driver makes of `input` arriving, in `chunk`s of at most that many bytes, as the
/// replies to an instruction that expects status packets from `expect` with `count` data bytes
/// each: the same framing, matching and checks as a real exchange, without a port — for
/// checking a capture of bus traffic, or fuzzing the driver's reply handling.
///
/// ```
/// use hand_control::protocol::{encode, instruction_id};
/// use hand_control::{Error, decode_replies};
///
/// // Two servos answer a 2-byte read; servo 2's status has its alert bit set.
/// let mut wire = Vec::new();
/// encode(&mut wire, 1, instruction_id::STATUS, &[0x00, 0x34, 0x12]);
/// encode(&mut wire, 2, instruction_id::STATUS, &[0x80, 0x00, 0x08]);
/// let answers = decode_replies(&wire, 5, &[1, 2], 2)?;
/// assert_eq!(answers, [(1, false, vec![0x34, 0x12]), (2, true, vec![0x00, 0x08])]);
/// // Servo 2 never answers: its timeout, as on the bus.
/// let one = &wire[..wire.len() / 2];
/// assert!(matches!(decode_replies(one, 64, &[1, 2], 2), Err(Error::Timeout { id: Some(2) })));
/// # Ok::<(), hand_control::Error>(())
/// ```
///
/// # Errors
/// The error the exchange would return.
pub fn decode_replies(
    input: &[u8],
    chunk: usize,
    expect: &[u8],
    count: u16,
) -> Result<Vec<DecodedAnswer>, Error> {
    let n = usize::from(count);
    let mut slots: Vec<Slot> = expect.iter().map(|_| Slot::Waiting).collect();
    let mut data = vec![0; expect.len() * n];
    let mut rx = Vec::new();
    let mut stray = None;
    for c in input.chunks(chunk.max(1)) {
        rx.extend_from_slice(c);
        take_answers(&mut rx, count, expect, &mut slots, &mut data, &mut stray);
    }
    outcome(&mut slots, expect, stray)?;
    Ok(slots
        .iter()
        .enumerate()
        .filter_map(|(k, s)| match *s {
            Slot::Answered { id, alert } => Some((id, alert, data[k * n..(k + 1) * n].to_vec())),
            _ => None,
        })
        .collect())
}

/// Checks a status packet: a status, no error code, `count` data bytes; its alert bit and data.
fn check(count: u16, id: u8, instruction: u8, params: &[u8]) -> Result<(bool, &[u8]), Error> {
    let bad = |detail: String| Error::Protocol {
        id: Some(id),
        detail,
    };
    if instruction != instruction_id::STATUS {
        return Err(bad(format!("instruction {instruction:#04x}, not a status")));
    }
    let (&err, data) = params
        .split_first()
        .ok_or_else(|| bad("no error byte".into()))?;
    if let Some(error) = InstructionError::from_code(err) {
        return Err(Error::Status { id, error });
    }
    if data.len() != usize::from(count) {
        return Err(bad(format!("{} data bytes, expected {count}", data.len())));
    }
    Ok((err & 0x80 != 0, data))
}

#[cfg(test)]
mod tests {
    use crate::protocol::{FrameError, Packet, Parser, encode};

    /// What the parser reports, in one shape.
    #[derive(Debug, PartialEq, Eq)]
    enum Seen {
        Packet(u8, u8, Vec<u8>),
        Crc(u8, u16, u16),
        BadLength,
    }

    fn with_parser(wire: &[u8], chunk: usize) -> Vec<Seen> {
        let mut p = Parser::default();
        let mut seen = Vec::new();
        for c in wire.chunks(chunk.max(1)) {
            p.push(c);
            while let Some(f) = p.next_packet() {
                seen.push(match f {
                    Ok(Packet {
                        id,
                        instruction,
                        params,
                        ..
                    }) => Seen::Packet(id, instruction, params),
                    Err(FrameError::Crc {
                        id, sent, computed, ..
                    }) => Seen::Crc(id, sent, computed),
                    Err(FrameError::BadLength) => Seen::BadLength,
                });
            }
        }
        seen
    }

    #[test]
    fn stuffed_status_unstuffs_in_place() {
        // Present Load −1 then a negative velocity: FF FF FD on the wire, one stuffing FD.
        let params = [0x00, 0xFF, 0xFF, 0xFD, 0xFF, 0xFF, 0xFF, 0x10, 0x20];
        let mut wire = vec![0x13, 0xFF];
        encode(&mut wire, 2, 0x55, &params);
        assert_eq!(
            with_parser(&wire, 3),
            [Seen::Packet(2, 0x55, params.to_vec())]
        );
    }

    #[test]
    fn a_bad_length_is_seen_with_seven_bytes() {
        // Header, ID and a LEN of 0xFFFF: garbage before any instruction byte has arrived.
        let wire = [0xFF, 0xFF, 0xFD, 0x00, 0xFF, 0xFF, 0xFF];
        assert_eq!(with_parser(&wire, 1), [Seen::BadLength]);
    }
}
