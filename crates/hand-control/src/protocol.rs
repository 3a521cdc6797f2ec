//! Protocol 2.0 framing for the device side: a streaming instruction-packet parser that
//! resynchronises on garbage, and a packet encoder with byte stuffing.
//!
//! `dynamixel2` is controller-only: it parses *status* packets and keeps its stuffing private.
//! Its public pieces are reused here — [`calculate_checksum`] (CRC-16/BUYPASS, polynomial
//! 0x8005) and the instruction / packet IDs. Framing per the e-Manual, "Protocol 2.0",
//! <https://emanual.robotis.com/docs/en/dxl/protocol2/>: `FF FF FD 00 | ID | LEN_L LEN_H |
//! INST | PARAM… | CRC_L CRC_H`, LEN = stuffed parameters + 3, CRC over everything before it,
//! and `FF FF FD` inside the body followed by an extra `FD`.

pub use dynamixel2::checksum::calculate_checksum;
pub use dynamixel2::instructions::{instruction_id, packet_id};

/// The highest servo ID (0xFD and 0xFF are reserved, 0xFE is broadcast).
pub const MAX_ID: u8 = 252;

/// The four bytes that open every packet.
pub const HEADER: [u8; 4] = [0xFF, 0xFF, 0xFD, 0x00];
/// The longest body (LEN field) the parser accepts; longer LEN values are taken as garbage.
/// 1 KiB covers a sync write to all 253 IDs of a 2-byte register (4 + 253 × 3 + 3 = 766).
pub const MAX_LEN: usize = 1024;

/// One decoded packet (byte stuffing already removed).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Packet {
    /// Packet ID (0…252, or 0xFE broadcast).
    pub id: u8,
    /// Instruction (for a status packet: 0x55).
    pub instruction: u8,
    /// Parameters, unstuffed.
    pub params: Vec<u8>,
    /// Bytes the packet took on the wire (for wire-time accounting).
    pub wire_len: usize,
}

/// A framing problem the parser found and skipped.
#[derive(Debug, Clone, PartialEq, Eq)]
#[non_exhaustive]
pub enum FrameError {
    /// A complete frame whose CRC did not match: the servo answers with a CRC error.
    Crc {
        /// The frame's ID byte.
        id: u8,
        /// The frame's instruction byte.
        instruction: u8,
        /// The CRC the frame carried.
        sent: u16,
        /// The CRC of the bytes received.
        computed: u16,
    },
    /// A LEN field below 3 or above [`MAX_LEN`].
    BadLength,
}

/// One packet as a view into the [`Parser`]'s buffer: what [`Parser::next_packet_ref`] returns
/// without allocating. It borrows the parser, so it lives until the parser's next call.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PacketRef<'a> {
    /// Packet ID (0…252, or 0xFE broadcast).
    pub id: u8,
    /// Instruction (for a status packet: 0x55).
    pub instruction: u8,
    /// Parameters, unstuffed.
    pub params: &'a [u8],
    /// Bytes the packet took on the wire (for wire-time accounting).
    pub wire_len: usize,
}

impl PacketRef<'_> {
    /// The packet with its parameters copied out.
    pub fn to_packet(&self) -> Packet {
        Packet {
            id: self.id,
            instruction: self.instruction,
            params: self.params.to_vec(),
            wire_len: self.wire_len,
        }
    }
}

/// A streaming parser: push received bytes, pop packets.
///
/// ```
/// use hand_control::protocol::{encode, Parser};
/// let mut wire = vec![0x00, 0x13]; // line noise before the packet
/// encode(&mut wire, 1, 0x01, &[]); // PING id 1
/// let mut p = Parser::default();
/// p.push(&wire);
/// let pkt = p.next_packet().unwrap().unwrap();
/// assert_eq!((pkt.id, pkt.instruction), (1, 0x01));
/// assert!(p.next_packet().is_none());
/// ```
#[derive(Debug, Default)]
pub struct Parser {
    buf: Vec<u8>,
    /// Bytes at the front of `buf` that the last [`PacketRef`] lent out; dropped on the next
    /// call, once the borrow has ended.
    lent: usize,
}

impl Parser {
    /// Appends received bytes.
    pub fn push(&mut self, bytes: &[u8]) {
        self.drop_lent();
        self.buf.extend_from_slice(bytes);
    }

    /// Bytes held, waiting for the rest of a packet.
    pub fn pending(&self) -> usize {
        self.buf.len() - self.lent
    }

    /// The next complete packet, a skipped bad frame, or `None` when more bytes are needed.
    pub fn next_packet(&mut self) -> Option<Result<Packet, FrameError>> {
        Some(self.next_packet_ref()?.map(|p| p.to_packet()))
    }

    /// [`next_packet`](Self::next_packet) without allocating: the packet's parameters are
    /// borrowed from the parser's buffer (a loop that only looks at them, as a servo or a
    /// status reader does, runs with no heap traffic once the buffer has grown).
    ///
    /// ```
    /// use hand_control::protocol::{encode, Parser};
    /// let mut wire = Vec::new();
    /// encode(&mut wire, 7, 0x02, &[132, 0, 4, 0]); // READ 4 bytes at 132 from id 7
    /// let mut p = Parser::default();
    /// p.push(&wire);
    /// let pkt = p.next_packet_ref().unwrap().unwrap();
    /// assert_eq!((pkt.id, pkt.instruction, pkt.params), (7, 0x02, &[132, 0, 4, 0][..]));
    /// assert!(p.next_packet_ref().is_none());
    /// assert_eq!(p.pending(), 0);
    /// ```
    pub fn next_packet_ref(&mut self) -> Option<Result<PacketRef<'_>, FrameError>> {
        self.drop_lent();
        Some(match next_frame(&mut self.buf)? {
            Ok(f) => {
                self.lent = f.total;
                Ok(PacketRef {
                    id: f.id,
                    instruction: f.instruction,
                    params: &self.buf[8..8 + f.params],
                    wire_len: f.total,
                })
            }
            Err(e) => Err(e),
        })
    }

    fn drop_lent(&mut self) {
        self.buf.drain(..std::mem::take(&mut self.lent));
    }
}

/// A frame with a good CRC that [`next_frame`] left at the front of the buffer: its unstuffed
/// parameters are `buf[8..8 + params]`; the caller drops its `total` bytes once done with them.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Framed {
    pub(crate) id: u8,
    pub(crate) instruction: u8,
    pub(crate) params: usize,
    pub(crate) total: usize,
}

/// The one Protocol 2.0 framing, in place: resynchronise on a header, LEN in `3..=MAX_LEN`,
/// CRC-16, e-Manual unstuffing of the parameters inside `buf` (no new `Vec`), bad frames
/// skipped one byte at a time (and reported). `None` when more bytes are needed. [`Parser::next_packet`]
/// and the driver's status reader both frame through it.
pub(crate) fn next_frame(buf: &mut Vec<u8>) -> Option<Result<Framed, FrameError>> {
    let start = find_header(buf);
    buf.drain(..start);
    let &[_, _, _, _, id, len_lo, len_hi, ..] = buf.as_slice() else {
        return None;
    };
    let len = usize::from(u16::from_le_bytes([len_lo, len_hi]));
    if !(3..=MAX_LEN).contains(&len) {
        // Not a real header: drop its first byte and look again.
        buf.drain(..1);
        return Some(Err(FrameError::BadLength));
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
        return Some(Err(FrameError::Crc {
            id,
            instruction,
            sent,
            computed,
        }));
    }
    let params = unstuff_in_place(&mut buf[8..crc_at]);
    Some(Ok(Framed {
        id,
        instruction,
        params,
        total,
    }))
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

/// [`unstuff`] in place: every `FF FF FD FD` becomes `FF FF FD`; returns the
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

/// Removes byte stuffing: every `FF FF FD FD` on the wire becomes `FF FF FD`.
pub fn unstuff(body: &[u8]) -> Vec<u8> {
    let mut out = body.to_vec();
    let n = unstuff_in_place(&mut out);
    out.truncate(n);
    out
}

/// Appends one packet — header, `id`, LEN, `instruction`, stuffed `params`, CRC — to `out`.
/// A status packet is `instruction` 0x55 with the error byte as the first parameter.
///
/// ```
/// use hand_control::protocol::encode;
/// let mut out = Vec::new();
/// encode(&mut out, 1, 0x01, &[]);
/// // The e-Manual's PING example: FF FF FD 00 01 03 00 01 19 4E.
/// assert_eq!(out, [0xFF, 0xFF, 0xFD, 0x00, 0x01, 0x03, 0x00, 0x01, 0x19, 0x4E]);
/// ```
pub fn encode(out: &mut Vec<u8>, id: u8, instruction: u8, params: &[u8]) {
    let start = out.len();
    out.extend_from_slice(&HEADER);
    out.extend_from_slice(&[id, 0, 0, instruction]);
    let body = out.len();
    for &b in params {
        out.push(b);
        if out.len() - body >= 3 && out[out.len() - 3..] == [0xFF, 0xFF, 0xFD] {
            out.push(0xFD);
        }
    }
    let len = (out.len() - body + 3) as u16;
    out[start + 5..start + 7].copy_from_slice(&len.to_le_bytes());
    let crc = calculate_checksum(0, &out[start..]);
    out.extend_from_slice(&crc.to_le_bytes());
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stuffing_round_trips_the_emanual_pattern() {
        let params = [0xFF, 0xFF, 0xFD, 0x00, 0xFF, 0xFF, 0xFD, 0xFD, 0x01];
        let mut wire = Vec::new();
        encode(&mut wire, 7, 0x03, &params);
        // Two patterns → two stuffing bytes.
        assert_eq!(wire.len(), 10 + params.len() + 2);
        let mut p = Parser::default();
        p.push(&wire);
        assert_eq!(
            p.next_packet(),
            Some(Ok(Packet {
                id: 7,
                instruction: 3,
                params: params.to_vec(),
                wire_len: wire.len()
            }))
        );
    }

    #[test]
    fn crc_error_is_reported_then_the_next_packet_found() {
        let mut wire = Vec::new();
        encode(&mut wire, 1, 0x01, &[]);
        let n = wire.len();
        wire[n - 1] ^= 0xFF;
        encode(&mut wire, 2, 0x01, &[]);
        let mut p = Parser::default();
        p.push(&wire);
        assert!(matches!(
            p.next_packet(),
            Some(Err(FrameError::Crc {
                id: 1,
                instruction: 1,
                ..
            }))
        ));
        assert_eq!(p.next_packet().map(|r| r.map(|k| k.id)), Some(Ok(2)));
    }
}
