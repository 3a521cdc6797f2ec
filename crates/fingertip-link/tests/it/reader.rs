//! The reader on streams as a UART delivers them: joined mid-frame, with noise, a flipped bit,
//! a lost byte.

use fingertip_link::{Frame, FrameError, FrameReader, LEN};
use proptest::prelude::*;

fn frame(seq: u8) -> Frame {
    Frame {
        seq,
        t_us: u32::from(seq) * 6180,
        pressure_pa: [101_000 + i32::from(seq), 101_100, 100_900],
        tared: true,
        force_gf: Some(f32::from(seq)),
        ..Frame::default()
    }
}

fn read(bytes: &[u8]) -> (Vec<Result<Frame, FrameError>>, FrameReader) {
    let mut reader = FrameReader::new();
    let got = bytes.iter().filter_map(|&b| reader.push(b)).collect();
    (got, reader)
}

#[test]
fn noise_with_sync_bytes_before_a_frame_is_skipped_and_counted() {
    let mut bytes = vec![0xA5, 0x00, 0xA5, 0xA5, 0x13];
    bytes.extend_from_slice(&frame(1).encode());
    let (got, reader) = read(&bytes);
    assert_eq!(got, vec![Ok(frame(1))]);
    assert_eq!((reader.dropped_bytes(), reader.bad_frames()), (5, 0));
}

#[test]
fn a_flipped_bit_costs_that_frame_only() {
    let mut bytes = Vec::new();
    for seq in 0..3 {
        bytes.extend_from_slice(&frame(seq).encode());
    }
    bytes[LEN + 12] ^= 0x10;
    let (got, reader) = read(&bytes);
    assert_eq!(got.len(), 3);
    assert_eq!(got[0], Ok(frame(0)));
    assert!(matches!(got[1], Err(FrameError::Checksum { .. })));
    assert_eq!(got[2], Ok(frame(2)));
    assert_eq!(
        (reader.dropped_bytes(), reader.bad_frames()),
        (LEN as u64, 1)
    );
}

#[test]
fn a_lost_byte_costs_one_frame_and_the_next_sync_is_found_inside_it() {
    let mut bytes = Vec::new();
    for seq in 0..3 {
        bytes.extend_from_slice(&frame(seq).encode());
    }
    // Frame 1 loses a byte: its 27 bytes and frame 2's first byte make a damaged frame; the
    // reader finds frame 2's sync inside it.
    bytes.remove(LEN + 5);
    let (got, reader) = read(&bytes);
    let good: Vec<_> = got
        .iter()
        .filter_map(|r| r.as_ref().ok())
        .copied()
        .collect();
    assert_eq!(good, vec![frame(0), frame(2)]);
    assert_eq!(reader.bad_frames(), 1);
    assert_eq!(reader.dropped_bytes(), LEN as u64 - 1);
}

proptest! {
    /// Whatever the line carries, the reader never panics, and every frame it returns is one
    /// whose bytes were on the line.
    #[test]
    fn any_stream_yields_only_frames_that_were_sent(
        noise in proptest::collection::vec(any::<u8>(), 0..200),
        cut in 0usize..200,
    ) {
        let sent = frame(42);
        let mut bytes = noise.clone();
        let at = cut.min(bytes.len());
        bytes.splice(at..at, sent.encode());
        let (got, _) = read(&bytes);
        for f in got.into_iter().flatten() {
            prop_assert_eq!(f.encode().len(), LEN);
            let encoded = f.encode();
            prop_assert!(bytes.windows(LEN).any(|w| w == encoded));
        }
    }
}
