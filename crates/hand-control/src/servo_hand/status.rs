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
//! Replies are framed in place ([`next_frame`]: [`crate::protocol::Parser`]'s framing, without
//! its per-packet `Vec`) into buffers the [`Link`] keeps, so a steady exchange allocates
//! nothing; unit tests hold the two framings equal on random streams.

use std::time::{Duration, Instant};

use dynamixel2::Bus;
use dynamixel2::instructions::instruction_id;
use dynamixel2::serial2::SerialPort;

use crate::InstructionError;
use crate::error::Error;
use crate::protocol::{HEADER, MAX_LEN, calculate_checksum};

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
        })
    }

    /// Makes room for exchanges of up to `answers` status packets of `count` data bytes each,
    /// so they allocate nothing.
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
            while let Some(frame) = next_frame(&mut self.rx) {
                let (from, result, used) = match frame {
                    Frame::Packet {
                        id,
                        instruction,
                        params,
                        total,
                    } => {
                        let body = self.rx.get(8..8 + params).unwrap_or_default();
                        (id, check(count, id, instruction, body), total)
                    }
                    Frame::Crc { id, sent, computed } => (
                        id,
                        Err(Error::Crc {
                            id: Some(id),
                            message: sent,
                            computed,
                        }),
                        0,
                    ),
                    Frame::BadLength => continue,
                };
                // A corrupted ID byte: charge the error to the first servo still waiting.
                let slot = expect
                    .iter()
                    .zip(&self.slots)
                    .position(|(&i, s)| i == from && matches!(s, Slot::Waiting))
                    .or_else(|| self.slots.iter().position(|s| matches!(s, Slot::Waiting)));
                match (slot, result) {
                    (Some(k), Ok((alert, data))) => {
                        // `check` made `data` exactly `count` bytes long.
                        if let Some(d) = self.data.get_mut(k * n..(k + 1) * n) {
                            d.copy_from_slice(data);
                        }
                        self.slots[k] = Slot::Answered { id: from, alert };
                    }
                    (Some(k), Err(e)) => self.slots[k] = Slot::Failed(e),
                    (None, _) => {
                        stray.get_or_insert_with(|| Error::Protocol {
                            id: Some(from),
                            detail: "a status packet nobody asked for".into(),
                        });
                    }
                }
                self.rx.drain(..used);
            }
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
                Err(e) if e.kind() == std::io::ErrorKind::TimedOut => {}
                Err(e) => return Err(Error::Io(e)),
            }
        }
        for (slot, &id) in self.slots.iter_mut().zip(expect) {
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
}

/// What [`next_frame`] found at the front of the received bytes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Frame {
    /// A frame with a good CRC, still at the front of the buffer: its unstuffed parameters are
    /// `buf[8..8 + params]`; the caller drops its `total` bytes once done with them.
    Packet {
        id: u8,
        instruction: u8,
        params: usize,
        total: usize,
    },
    /// A complete frame whose CRC did not match (its first byte dropped).
    Crc { id: u8, sent: u16, computed: u16 },
    /// A LEN field below 3 or above [`MAX_LEN`] (its first byte dropped).
    BadLength,
}

/// [`crate::protocol::Parser::next_packet`] in place: the same framing (resynchronise on a
/// header, LEN in `3..=MAX_LEN`, CRC-16, e-Manual unstuffing), the same skipping of bad frames,
/// but the parameters are unstuffed inside `buf` instead of into a new `Vec`. `None` when more
/// bytes are needed. The unit tests check both against each other.
fn next_frame(buf: &mut Vec<u8>) -> Option<Frame> {
    let start = find_header(buf);
    buf.drain(..start);
    let &[_, _, _, _, id, len_lo, len_hi, ..] = buf.as_slice() else {
        return None;
    };
    let len = usize::from(u16::from_le_bytes([len_lo, len_hi]));
    if !(3..=MAX_LEN).contains(&len) {
        // Not a real header: drop its first byte and look again.
        buf.drain(..1);
        return Some(Frame::BadLength);
    }
    let total = 7 + len;
    let crc_at = total - 2;
    let (Some(body), Some(&[lo, hi])) = (buf.get(..crc_at), buf.get(crc_at..total)) else {
        return None;
    };
    // LEN ≥ 3, so `crc_at` ≥ 8: the body holds the instruction byte.
    let instruction = body[7];
    let sent = u16::from_le_bytes([lo, hi]);
    let computed = calculate_checksum(0, body);
    if computed != sent {
        // Garbage that happened to contain a header: resume one byte later, so a real packet
        // inside it is still found.
        buf.drain(..1);
        return Some(Frame::Crc { id, sent, computed });
    }
    let params = unstuff_in_place(&mut buf[8..crc_at]);
    Some(Frame::Packet {
        id,
        instruction,
        params,
        total,
    })
}

/// Position of the first (possibly partial, at the end) header in `buf`; `buf.len()` if none.
fn find_header(buf: &[u8]) -> usize {
    (0..buf.len())
        .find(|&i| {
            let n = HEADER.len().min(buf.len() - i);
            buf[i..i + n] == HEADER[..n]
        })
        .unwrap_or(buf.len())
}

/// [`crate::protocol::unstuff`] in place: every `FF FF FD FD` becomes `FF FF FD`; returns the
/// unstuffed length (the front of `body`).
fn unstuff_in_place(body: &mut [u8]) -> usize {
    // The last three wire bytes; cleared after a stuffing byte so patterns never chain.
    let mut last = [0u8; 3];
    let mut out = 0;
    for i in 0..body.len() {
        let b = body[i];
        if last == [0xFF, 0xFF, 0xFD] && b == 0xFD {
            last = [0; 3];
            continue;
        }
        body[out] = b;
        out += 1;
        last = [last[1], last[2], b];
    }
    out
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
    use super::*;
    use crate::protocol::{FrameError, Packet, Parser, encode};
    use proptest::prelude::*;

    /// What either parser reports, in one shape.
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

    fn in_place(wire: &[u8], chunk: usize) -> Vec<Seen> {
        let mut buf = Vec::new();
        let mut seen = Vec::new();
        for c in wire.chunks(chunk.max(1)) {
            buf.extend_from_slice(c);
            while let Some(f) = next_frame(&mut buf) {
                seen.push(match f {
                    Frame::Packet {
                        id,
                        instruction,
                        params,
                        total,
                    } => {
                        let s = Seen::Packet(id, instruction, buf[8..8 + params].to_vec());
                        buf.drain(..total);
                        s
                    }
                    Frame::Crc { id, sent, computed } => Seen::Crc(id, sent, computed),
                    Frame::BadLength => Seen::BadLength,
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
        assert_eq!(in_place(&wire, 3), [Seen::Packet(2, 0x55, params.to_vec())]);
    }

    #[test]
    fn a_bad_length_is_seen_with_seven_bytes() {
        // Header, ID and a LEN of 0xFFFF: garbage before any instruction byte has arrived.
        let wire = [0xFF, 0xFF, 0xFD, 0x00, 0xFF, 0xFF, 0xFF];
        assert_eq!(in_place(&wire, 1), [Seen::BadLength]);
        assert_eq!(with_parser(&wire, 1), [Seen::BadLength]);
    }

    /// A stream of packets (some with stuffing patterns), garbage and corrupted bytes.
    fn stream() -> impl Strategy<Value = Vec<u8>> {
        let piece = prop_oneof![
            (
                any::<u8>(),
                any::<u8>(),
                prop::collection::vec(prop_oneof![Just(0xFFu8), Just(0xFD), any::<u8>()], 0..24),
            )
                .prop_map(|(id, ins, params)| {
                    let mut w = Vec::new();
                    encode(&mut w, id, ins, &params);
                    w
                }),
            prop::collection::vec(
                prop_oneof![Just(0xFFu8), Just(0xFD), Just(0), any::<u8>()],
                0..12
            ),
        ];
        (
            prop::collection::vec(piece, 0..8),
            prop::collection::vec((any::<prop::sample::Index>(), any::<u8>()), 0..3),
        )
            .prop_map(|(pieces, flips)| {
                let mut wire: Vec<u8> = pieces.concat();
                if !wire.is_empty() {
                    for (at, x) in flips {
                        let i = at.index(wire.len());
                        wire[i] ^= x;
                    }
                }
                wire
            })
    }

    proptest! {
        #[test]
        fn in_place_framing_matches_the_parser(wire in stream(), chunk in 1usize..64) {
            prop_assert_eq!(in_place(&wire, chunk), with_parser(&wire, chunk));
        }
    }
}
