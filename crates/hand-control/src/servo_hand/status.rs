//! Sync read with this crate's status-packet parser.
//!
//! `dynamixel2` 0.9.1 removes byte stuffing with a matcher that restarts from zero on a
//! mismatch, so a status packet whose data holds `FF FF FF FD` (e.g. Present Load −1 followed by
//! a negative Present Velocity) keeps its stuffing byte and fails with `InvalidParameterCount`.
//! The e-Manual's rule ("FF FF FD" anywhere in the body gets an extra FD) is what
//! [`crate::protocol`] implements, so replies are read with it; sending still uses `dynamixel2`
//! (the driver's goals are non-negative and never contain the pattern).

use std::time::{Duration, Instant};

use dynamixel2::Bus;
use dynamixel2::instructions::{instruction_id, packet_id};

use crate::InstructionError;
use crate::error::Error;
use crate::protocol::{FrameError, Parser};

/// One servo's answer to a sync read.
pub(super) struct Answer {
    pub(super) id: u8,
    pub(super) alert: bool,
    pub(super) data: Vec<u8>,
}

/// The ROBOTIS SDK's flat allowance per answer, as `dynamixel2` also uses.
const LATENCY: Duration = Duration::from_millis(34);

/// Sends SYNC READ for `ids` and collects each answer in order.
///
/// # Errors
/// The first servo's failure; every servo's answer (or timeout) is consumed first.
pub(super) fn sync_read(
    bus: &mut Bus<Vec<u8>, Vec<u8>>,
    ids: &[u8],
    address: u16,
    count: u16,
) -> Result<Vec<Answer>, Error> {
    bus.write_instruction(
        packet_id::BROADCAST,
        instruction_id::SYNC_READ,
        4 + ids.len(),
        |b| {
            b[..2].copy_from_slice(&address.to_le_bytes());
            b[2..4].copy_from_slice(&count.to_le_bytes());
            b[4..].copy_from_slice(ids);
        },
    )
    .map_err(Error::from_write)?;
    let baud = u64::from(bus.baud_rate().max(1));
    let per_answer =
        LATENCY + Duration::from_nanos((11 + u64::from(count)) * 10 * 1_000_000_000 / baud);
    // Answers are matched to servos by ID, so one missing status packet is that servo's
    // timeout and does not shift the others.
    let deadline = Instant::now() + per_answer * ids.len().max(1) as u32;
    let port = bus.serial_port();
    let mut parser = Parser::default();
    let mut buf = [0u8; 512];
    let mut results: Vec<Option<Result<Answer, Error>>> = ids.iter().map(|_| None).collect();
    let mut stray = None;
    while results.iter().any(Option::is_none) && Instant::now() < deadline {
        while let Some(frame) = parser.next_packet() {
            let (slot_id, result) = match frame {
                Ok(p) => (p.id, check(p.id, count, p)),
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
            let slot = ids
                .iter()
                .zip(&results)
                .position(|(&i, r)| i == slot_id && r.is_none())
                .or_else(|| results.iter().position(Option::is_none));
            match slot {
                Some(k) => results[k] = Some(result),
                None => {
                    stray.get_or_insert(Error::Protocol {
                        id: Some(slot_id),
                        detail: "status packet nobody was asked for".into(),
                    });
                }
            }
        }
        if results.iter().all(Option::is_some) {
            break;
        }
        match port.read(&mut buf) {
            Ok(n) => parser.push(&buf[..n]),
            Err(e) if e.kind() == std::io::ErrorKind::TimedOut => {}
            Err(e) => return Err(Error::Io(e)),
        }
    }
    let mut out = Vec::with_capacity(ids.len());
    for (&id, r) in ids.iter().zip(results) {
        out.push(r.unwrap_or(Err(Error::Timeout { id: Some(id) }))?);
    }
    match stray {
        Some(e) => Err(e),
        None => Ok(out),
    }
}

/// Checks servo `id`'s status packet: a status, no error code, `count` data bytes.
fn check(id: u8, count: u16, p: crate::protocol::Packet) -> Result<Answer, Error> {
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
