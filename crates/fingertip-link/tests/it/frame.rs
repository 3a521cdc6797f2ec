//! Encoding and decoding: Fletcher-16 against its published vectors, a whole frame against
//! bytes computed independently of this crate, and every field's range.

use fingertip_link::{Frame, FrameError, LEN, fletcher16};
use proptest::prelude::*;

/// Fletcher-16's test vectors (Wikipedia, "Fletcher's checksum", § Test vectors; the sums of
/// RFC 1146's algorithm over 8-bit words).
#[test]
fn fletcher16_matches_its_published_vectors() {
    assert_eq!(fletcher16(b"abcde"), 0xC8F0);
    assert_eq!(fletcher16(b"abcdef"), 0x2057);
    assert_eq!(fletcher16(b"abcdefgh"), 0x0627);
}

/// A frame's bytes computed by hand from the format's table (Python's `struct.pack('<…')` and
/// the RFC 1146 sums): seq 7, tared and in contact, 1 s, three pressures, 49.5 gf, grid cell 4,
/// pad cell 14, torque 300.
const VECTOR: [u8; LEN] = [
    0xA5, 0x5A, 0x07, 0x03, 0x40, 0x42, 0x0F, 0x00, 0xCD, 0x8B, 0x01, 0x00, 0x22, 0x8C, 0x01, 0x00,
    0xB4, 0x8B, 0x01, 0x00, 0xEF, 0x01, 0x04, 0x0E, 0x2C, 0x01, 0x17, 0xC6,
];

fn vector_frame() -> Frame {
    Frame {
        seq: 7,
        t_us: 1_000_000,
        pressure_pa: [101_325, 101_410, 101_300],
        tared: true,
        in_contact: true,
        fault: false,
        force_gf: Some(49.5),
        grid_cell: Some(4),
        pad_cell: Some(14),
        torque_raw: 300,
    }
}

#[test]
fn a_frame_encodes_to_the_independently_computed_bytes_and_back() {
    assert_eq!(vector_frame().encode(), VECTOR);
    assert_eq!(Frame::decode(&VECTOR), Ok(vector_frame()));
}

#[test]
fn a_fault_frame_carries_only_the_flag_and_the_safe_torque() {
    let f = Frame::decode(&Frame::fault(5, 9).encode()).expect("valid");
    assert!(f.fault && !f.tared && !f.in_contact);
    assert_eq!((f.seq, f.t_us, f.torque_raw), (9, 5, 0));
    assert_eq!((f.force_gf, f.grid_cell, f.pad_cell), (None, None, None));
}

#[test]
fn force_is_sent_in_tenths_rounded_half_up_and_never_negative() {
    let sent = |g: f32| {
        Frame::decode(
            &Frame {
                force_gf: Some(g),
                ..Frame::default()
            }
            .encode(),
        )
        .expect("valid")
        .force_gf
    };
    assert_eq!(sent(12.34), Some(12.3));
    assert_eq!(sent(12.35), Some(12.4));
    assert_eq!(sent(-3.0), Some(0.0));
    assert_eq!(sent(f32::NAN), Some(0.0));
    assert_eq!(sent(1e9), Some(6553.4));
}

#[test]
fn damaged_or_foreign_bytes_are_typed_errors() {
    let mut b = VECTOR;
    b[0] = 0x00;
    assert_eq!(Frame::decode(&b), Err(FrameError::Sync([0x00, 0x5A])));
    let mut b = VECTOR;
    b[9] ^= 0x01;
    assert!(matches!(
        Frame::decode(&b),
        Err(FrameError::Checksum {
            carried: 0xC617,
            ..
        })
    ));
    // Checksum-valid frames with values the fingertip never sends.
    let reseal = |i: usize, v: u8| {
        let mut b = VECTOR;
        b[i] = v;
        let sum = fletcher16(&b[..LEN - 2]).to_le_bytes();
        b[LEN - 2..].copy_from_slice(&sum);
        Frame::decode(&b)
    };
    let field = |r: Result<Frame, FrameError>| match r {
        Err(FrameError::Field { field, value }) => (field, value),
        other => panic!("{other:?}"),
    };
    assert_eq!(field(reseal(22, 9)), ("Arrival-of-Time cell", 9));
    assert_eq!(field(reseal(23, 24)), ("contact MLP cell", 24));
    assert_eq!(field(reseal(25, 0x04)), ("torque", 0x042C));
    assert_eq!(field(reseal(3, 0x08)), ("flags", 8));
    let e = reseal(23, 24).expect_err("refused");
    assert_eq!(
        e.to_string(),
        "frame's contact MLP cell is 24, which the fingertip never sends"
    );
}

fn any_frame() -> impl Strategy<Value = Frame> {
    (
        any::<u8>(),
        any::<u32>(),
        any::<[i32; 3]>(),
        any::<[bool; 3]>(),
        proptest::option::of(0u16..0xFFFF),
        proptest::option::of(0u8..9),
        proptest::option::of(0u8..24),
        0u16..=1023,
    )
        .prop_map(
            |(seq, t_us, pressure_pa, [tared, in_contact, fault], force, grid, pad, torque)| {
                Frame {
                    seq,
                    t_us,
                    pressure_pa,
                    tared,
                    in_contact,
                    fault,
                    force_gf: force.map(|d| f32::from(d) / 10.0),
                    grid_cell: grid,
                    pad_cell: pad,
                    torque_raw: torque,
                }
            },
        )
}

proptest! {
    #[test]
    fn every_frame_decodes_to_itself(frame in any_frame()) {
        prop_assert_eq!(Frame::decode(&frame.encode()), Ok(frame));
    }

    #[test]
    fn any_bytes_decode_or_fail_typed(bytes in any::<[u8; LEN]>()) {
        if let Ok(frame) = Frame::decode(&bytes) {
            prop_assert_eq!(frame.encode(), bytes);
        }
    }
}
