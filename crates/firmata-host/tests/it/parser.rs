//! The parser under what a serial line delivers: reports interleaved with a reply, sysex cut
//! short, stray and unknown bytes, overlong sysex, and arbitrary bytes (never a panic).

use firmata_host::parser::{Event, FrameError, Parser, SYSEX_CAPACITY, parse_stream};
use proptest::prelude::*;

fn all(stream: &[u8]) -> Vec<Result<String, FrameError>> {
    let mut out = Vec::new();
    parse_stream(stream, |r| out.push(r.map(|e| format!("{e:?}"))));
    out
}

#[test]
fn reports_between_a_request_and_its_reply_are_all_delivered() {
    let mut stream = vec![0xE0, 0x10, 0x02, 0x91, 0x01, 0x00];
    firmata_host::protocol::encode_i2c_reply(&mut stream, 0x68, 0x75, &[0x03]);
    stream.extend_from_slice(&[0xE1, 0x7F, 0x07]);
    let got = all(&stream);
    assert_eq!(got.len(), 4);
    assert!(got.iter().all(Result::is_ok), "{got:?}");
    assert!(
        got[2]
            .as_ref()
            .unwrap()
            .starts_with("I2cReply { address: 104, register: 117")
    );
}

#[test]
fn a_status_byte_inside_a_sysex_cuts_it_and_starts_its_own_message() {
    // A capability response losing its tail, then an analog report.
    let got = all(&[0xF0, 0x6C, 0x00, 0x01, 0xE2, 0x05, 0x00]);
    assert_eq!(
        got[0],
        Err(FrameError::TruncatedSysex {
            id: Some(0x6C),
            len: 3
        })
    );
    assert_eq!(got[1].as_deref(), Ok("Analog { channel: 2, value: 5 }"));
    // An analog message cut by a version report.
    let got = all(&[0xE0, 0x05, 0xF9, 2, 5]);
    assert_eq!(got[0], Err(FrameError::TruncatedMessage { command: 0xE0 }));
    assert_eq!(got[1].as_deref(), Ok("Version { major: 2, minor: 5 }"));
    // An empty sysex and one cut before its ID.
    assert_eq!(
        all(&[0xF0, 0xF7]),
        [Err(FrameError::TruncatedSysex { id: None, len: 0 })]
    );
}

#[test]
fn stray_and_unknown_bytes_are_errors_and_parsing_goes_on() {
    let got = all(&[0x42, 0xF2, 0xA5, 0x01, 0xF9, 2, 6]);
    assert_eq!(
        &got[..4],
        [
            Err(FrameError::StrayData(0x42)),
            Err(FrameError::UnknownCommand(0xF2)),
            Err(FrameError::UnknownCommand(0xA5)),
            Err(FrameError::StrayData(0x01)),
        ]
    );
    assert_eq!(got[4].as_deref(), Ok("Version { major: 2, minor: 6 }"));
}

#[test]
fn malformed_and_overlong_sysex_are_errors() {
    // An I2C reply with an odd data length.
    assert_eq!(
        all(&[0xF0, 0x77, 0x68, 0x00, 0x75, 0x00, 0x03, 0xF7]),
        [Err(FrameError::Malformed { id: 0x77, len: 5 })]
    );
    let mut long = vec![0xF0, 0x71];
    long.extend(std::iter::repeat_n(0x41, SYSEX_CAPACITY + 10));
    long.push(0xF7);
    long.extend_from_slice(&[0xF9, 2, 6]);
    let got = all(&long);
    assert_eq!(got[0], Err(FrameError::SysexOverflow { id: 0x71 }));
    assert!(got[1].is_ok());
    // An unknown but well-framed sysex is a message, not an error.
    assert_eq!(
        all(&[0xF0, 0x61, 0x01, 0xF7])[0].as_deref(),
        Ok("Sysex { id: 97, payload: [1] }")
    );
}

/// Found by the fuzz target `firmata` (`fuzz/regressions/firmata/i2c-reply-14-bit-address`):
/// an I2C reply whose address bytes say 0x264C was read as a reply from 0x4C, its upper bits
/// dropped. The host asks 7-bit addresses only, so such a reply answers none of its requests.
#[test]
fn an_i2c_reply_from_an_address_beyond_7_bits_is_malformed() {
    assert_eq!(
        all(&[0xF0, 0x77, 0x4C, 0x4C, 0x4C, 0x4C, 0xF7]),
        [Err(FrameError::Malformed { id: 0x77, len: 4 })]
    );
    // 0x177 is not 0x77, nor 0xF7 a byte.
    for high in [0x01, 0x02] {
        let mut reply = Vec::new();
        firmata_host::protocol::encode_i2c_reply(&mut reply, 0x77, 0xA2, &[0x9C]);
        reply[3] = high;
        assert_eq!(
            all(&reply),
            [Err(FrameError::Malformed { id: 0x77, len: 6 })]
        );
    }
}

/// Found by the fuzz target `firmata` (`fuzz/regressions/firmata/cut-overlong-sysex`): a sysex
/// longer than the buffer and then cut by a status byte reported the buffer's length, not the
/// bytes received.
#[test]
fn a_cut_overlong_sysex_counts_every_byte_received() {
    let mut long = vec![0xF0, 0x71];
    long.extend(std::iter::repeat_n(0x41, SYSEX_CAPACITY + 10));
    long.extend_from_slice(&[0xF9, 2, 6]);
    let got = all(&long);
    assert_eq!(
        got[0],
        Err(FrameError::TruncatedSysex {
            id: Some(0x71),
            len: SYSEX_CAPACITY + 11
        })
    );
    assert_eq!(got[1].as_deref(), Ok("Version { major: 2, minor: 6 }"));
    // At the capacity exactly, the sysex is kept whole.
    let mut full = vec![0xF0, 0x71];
    full.extend(std::iter::repeat_n(0x41, SYSEX_CAPACITY - 1));
    full.push(0xF7);
    assert!(
        all(&full)[0]
            .as_deref()
            .is_ok_and(|e| e.starts_with("Text("))
    );
}

proptest! {
    /// Any bytes: no panic, and each byte completes at most one message or error.
    #[test]
    fn arbitrary_bytes_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..4096)) {
        let mut n = 0;
        parse_stream(&bytes, |_| n += 1);
        prop_assert!(n <= bytes.len());
    }

    /// Noise before a version report does not keep the report from being read.
    #[test]
    fn a_report_after_noise_is_read(noise in proptest::collection::vec(any::<u8>(), 0..256)) {
        let mut p = Parser::new();
        for b in noise { let _ = p.push(b); }
        let mut got = None;
        for b in [0xF9u8, 2, 5] {
            if let Some(Ok(Event::Version { major, minor })) = p.push(b) {
                got = Some((major, minor));
            }
        }
        prop_assert_eq!(got, Some((2, 5)));
    }

    /// Stepper integers survive the round trip within the firmware's 28 bits.
    #[test]
    fn stepper_integers_round_trip(v in -((1i32 << 28) - 1)..(1i32 << 28)) {
        let b = firmata_host::protocol::encode_stepper_i32(v).unwrap();
        prop_assert_eq!(firmata_host::protocol::decode_stepper_i32(b), v);
    }

    /// Custom floats keep six significant digits over the speeds a stepper runs at.
    #[test]
    fn custom_floats_round_trip(v in 1e-3f32..8.0e4) {
        let b = firmata_host::protocol::encode_custom_float(v).unwrap();
        let back = firmata_host::protocol::decode_custom_float(b);
        prop_assert!(((back - v) / v).abs() < 2e-6, "{} -> {}", v, back);
    }
}
