//! Dynamixel Protocol 2.0: what the driver makes of a servo's replies, and what the simulated
//! bus makes of a client's requests.
//!
//! Both take raw bytes (first byte < 0x80) or, from the first byte ≥ 0x80 on, a structured
//! list of frames that is encoded with a good CRC: random bytes almost never carry a valid
//! CRC-16, so the raw form alone would stop at the framing.

use std::time::Duration;

use arbitrary::{Arbitrary, Unstructured};
use dxl_sim::{SimConfig, answer_bytes};
use hand_control::decode_replies;
use hand_control::protocol::{MAX_ID, MAX_LEN, Parser, encode, instruction_id};

/// The servo IDs of the simulated bus and of the replies the driver expects.
pub const IDS: [u8; 3] = [1, 2, 3];

/// One frame of a structured input.
#[derive(Debug, Arbitrary)]
struct Frame {
    id: u8,
    instruction: u8,
    params: Vec<u8>,
    /// Flip the last CRC byte.
    corrupt: bool,
}

/// A structured input: garbage, frames, and how the bytes arrive.
#[derive(Debug, Arbitrary)]
struct Frames {
    garbage: Vec<u8>,
    frames: Vec<Frame>,
    chunk: u8,
}

impl Frames {
    fn wire(&self) -> Vec<u8> {
        let mut wire = self.garbage.clone();
        for f in &self.frames {
            let params = &f.params[..f.params.len().min(MAX_LEN - 3)];
            encode(&mut wire, f.id, f.instruction, params);
            if f.corrupt {
                if let Some(last) = wire.last_mut() {
                    *last ^= 0x5A;
                }
            }
        }
        wire
    }
}

/// The driver reading replies: `expect` the first `1 + data[1] % 3` of [`IDS`] with
/// `data[2] % 16` data bytes each.
///
/// Oracle: replies that are exactly one good status packet per expected servo, in order, with
/// the expected length, no error and nothing else on the wire, decode to their data.
pub fn status(data: &[u8]) {
    let data = crate::bounded(data);
    let [mode, n, count, rest @ ..] = data else {
        return;
    };
    let expect = &IDS[..1 + usize::from(*n % 3)];
    let count = u16::from(*count % 16);
    if *mode < 0x80 {
        let chunk = usize::from(*mode).max(1);
        let _ = decode_replies(rest, chunk, expect, count);
        return;
    }
    let Ok(input) = Frames::arbitrary_take_rest(Unstructured::new(rest)) else {
        return;
    };
    let wire = input.wire();
    let got = decode_replies(&wire, usize::from(input.chunk).max(1), expect, count);
    let well_formed = input.garbage.is_empty()
        && input.frames.len() == expect.len()
        && input.frames.iter().zip(expect).all(|(f, &id)| {
            f.id == id
                && f.instruction == instruction_id::STATUS
                && !f.corrupt
                && f.params.len() == 1 + usize::from(count)
                && f.params[0] & 0x7F == 0
        });
    if well_formed {
        let answers = got.unwrap_or_else(|e| panic!("good replies refused: {e}"));
        for ((id, alert, d), f) in answers.iter().zip(&input.frames) {
            assert_eq!(
                (*id, *alert, &d[..]),
                (f.id, f.params[0] & 0x80 != 0, &f.params[1..])
            );
        }
    }
}

/// The simulated bus (MX-28s with [`IDS`]) answering a client.
///
/// Oracle: whatever it is sent, everything the bus sends back frames as good status packets
/// from a servo ID (0…252: a client may rename a servo through its ID register, as on an
/// MX-28), the same through the owning and the borrowing parse.
pub fn sim(data: &[u8]) {
    let data = crate::bounded(data);
    let [mode, rest @ ..] = data else {
        return;
    };
    let (wire, chunk) = if *mode < 0x80 {
        (rest.to_vec(), usize::from(*mode).max(1))
    } else {
        match Frames::arbitrary_take_rest(Unstructured::new(rest)) {
            Ok(input) => (input.wire(), usize::from(input.chunk).max(1)),
            Err(_) => return,
        }
    };
    let answers = answer_bytes(
        &SimConfig::with_ids(&IDS),
        &wire,
        chunk,
        Duration::from_millis(100),
    );
    let (mut parser, mut borrowing) = (Parser::default(), Parser::default());
    parser.push(&answers);
    borrowing.push(&answers);
    while let Some(frame) = parser.next_packet() {
        let p = frame.unwrap_or_else(|e| panic!("the simulated bus sent a bad frame: {e:?}"));
        assert_eq!(p.instruction, instruction_id::STATUS, "{p:?}");
        assert!(p.id <= MAX_ID, "{p:?}");
        let r = borrowing.next_packet_ref();
        assert_eq!(r.map(|r| r.map(|r| r.to_packet())), Some(Ok(p)));
    }
    assert!(borrowing.next_packet_ref().is_none());
    assert_eq!(
        parser.pending(),
        0,
        "a partial frame from the simulated bus"
    );
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Found by `cargo xtask fuzz dxl_sim` (fuzz/regressions/dxl_sim/renamed-servo): a status
    /// from ID 0, which the first oracle took for a stranger. The input writes 0 to a servo's
    /// ID register (address 7), as a client may.
    #[test]
    fn a_servo_renamed_through_its_id_register_answers_under_its_new_id() {
        let data = include_bytes!("../../../fuzz/regressions/dxl_sim/renamed-servo");
        let input = Frames::arbitrary_take_rest(Unstructured::new(&data[1..])).expect("frames");
        let renames = input.frames.iter().any(|f| {
            f.instruction == instruction_id::WRITE
                && f.params.get(..2)
                    == Some(
                        &hand_control::control_table::MX_28
                            .register("ID")
                            .expect("ID")
                            .address
                            .to_le_bytes()[..],
                    )
                && f.params.get(2) == Some(&0)
        });
        assert!(renames, "{input:#?}");
        sim(data);
    }
}
