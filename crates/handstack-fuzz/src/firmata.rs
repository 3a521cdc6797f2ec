//! Firmata: what the host's parser (firmata-host) makes of the bytes a board sends.
//!
//! The input is raw bytes (first byte < 0x80: the stream is the rest, read in chunks of that
//! many bytes) or, from a first byte ≥ 0x80 on, a structured list of board reports made by
//! firmata-host's encoders, with noise between them and some cut short: random bytes seldom
//! make a sysex whose payload fits its ID's layout, so the raw form alone would mostly meet
//! the parser's error paths.
//!
//! The expected reports come from a second reading of the stream, written from the parser
//! module's docs rather than from its state machine (`expected`, below): the stream split at its
//! status bytes (bit 7 set), each run of data bytes after one read by that status byte's rule.

use std::ops::Range;

use arbitrary::{Arbitrary, Unstructured};
use firmata_host::parse_capabilities;
use firmata_host::parser::{Event, FrameError, Parser, SYSEX_CAPACITY, parse_stream};
use firmata_host::protocol as p;

/// What the parser must report at one byte of the stream.
#[derive(Debug, Clone, PartialEq, Eq)]
enum Expect {
    /// A message with two data bytes (analog, digital, version): its status and data bytes.
    Two { status: u8, data: [u8; 2] },
    /// A sysex closed by `F7` that fits the parser's buffer: its ID and where its payload is.
    Sysex { id: u8, payload: Range<usize> },
    /// A framing error.
    Error(FrameError),
}

/// How a status byte frames what follows it (protocol.md 2.6.0, "Message Types").
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Rule {
    /// Analog (`E0|ch`), digital (`90|port`), version (`F9`): two data bytes.
    Two,
    /// `F0`: data bytes up to `F7`.
    Sysex,
    /// A status byte no board sends: its data bytes are stray.
    Unknown,
}

fn rule(status: u8) -> Rule {
    match status {
        0x90..=0x9F | 0xE0..=0xEF | p::REPORT_VERSION => Rule::Two,
        p::START_SYSEX => Rule::Sysex,
        _ => Rule::Unknown,
    }
}

/// What is open when the next status byte arrives.
enum Open {
    Nothing,
    /// A two-byte message short of its data: its status byte.
    Two(u8),
    /// A sysex: the place of its bytes after `F0`.
    Sysex(Range<usize>),
}

/// Every report the parser must make on `wire`, each with the index of the byte that
/// completes it, by the parser module's docs: a status byte ends what is open (an `F7` closes
/// a sysex; any other status byte cuts the open message, and only the cut is reported at it)
/// and starts its own message; data bytes outside a message are stray; a sysex longer than
/// the buffer is an overflow; nothing open at the end of the input is reported.
fn expected(wire: &[u8]) -> Vec<(usize, Expect)> {
    let mut out = Vec::new();
    let next_status = |from: usize| {
        wire[from..]
            .iter()
            .position(|&b| b & 0x80 != 0)
            .map_or(wire.len(), |k| from + k)
    };
    let stray = |out: &mut Vec<(usize, Expect)>, run: Range<usize>| {
        out.extend(run.map(|k| (k, Expect::Error(FrameError::StrayData(wire[k])))));
    };
    let first = next_status(0);
    stray(&mut out, 0..first);
    let mut open = Open::Nothing;
    let mut s = first;
    while s < wire.len() {
        let status = wire[s];
        let end = next_status(s + 1);
        let starts = match std::mem::replace(&mut open, Open::Nothing) {
            Open::Sysex(body) if status == p::END_SYSEX => {
                out.push((s, sysex_end(wire, body)));
                None
            }
            Open::Sysex(body) => {
                let id = (!body.is_empty()).then(|| wire[body.start]);
                let cut = FrameError::TruncatedSysex {
                    id,
                    len: body.len(),
                };
                out.push((s, Expect::Error(cut)));
                Some(rule(status))
            }
            Open::Two(command) => {
                let cut = FrameError::TruncatedMessage { command };
                out.push((s, Expect::Error(cut)));
                Some(rule(status))
            }
            Open::Nothing => {
                if rule(status) == Rule::Unknown {
                    out.push((s, Expect::Error(FrameError::UnknownCommand(status))));
                }
                Some(rule(status))
            }
        };
        match starts {
            Some(Rule::Two) if end - s > 2 => {
                let data = [wire[s + 1], wire[s + 2]];
                out.push((s + 2, Expect::Two { status, data }));
                stray(&mut out, s + 3..end);
            }
            Some(Rule::Two) => open = Open::Two(status),
            Some(Rule::Sysex) => open = Open::Sysex(s + 1..end),
            Some(Rule::Unknown) | None => stray(&mut out, s + 1..end),
        }
        s = end;
    }
    out
}

/// A sysex closed by `F7`, `body` its bytes after `F0` (ID and payload).
fn sysex_end(wire: &[u8], body: Range<usize>) -> Expect {
    if body.is_empty() {
        return Expect::Error(FrameError::TruncatedSysex { id: None, len: 0 });
    }
    let id = wire[body.start];
    if body.len() > SYSEX_CAPACITY {
        return Expect::Error(FrameError::SysexOverflow { id });
    }
    Expect::Sysex {
        id,
        payload: body.start + 1..body.end,
    }
}

/// The bytes an event borrows from the parser's buffer.
fn borrowed<'a>(event: &Event<'a>) -> &'a [u8] {
    match *event {
        Event::Firmware { name, .. } => name,
        Event::Capabilities(b) | Event::AnalogMapping(b) | Event::Text(b) => b,
        Event::I2cReply { data, .. } => data,
        Event::Sysex { payload, .. } => payload,
        _ => &[],
    }
}

/// A formatter's output, dropped: displaying an error allocates nothing.
struct Discard;

impl std::fmt::Write for Discard {
    fn write_str(&mut self, _: &str) -> std::fmt::Result {
        Ok(())
    }
}

/// Checks one report of the parser against what the stream says it must be.
fn check(wire: &[u8], want: &Expect, got: Result<Event<'_>, FrameError>) {
    match &got {
        Err(e) => {
            use std::fmt::Write as _;
            write!(Discard, "{e}").expect("an error displays");
        }
        Ok(event) => {
            let b = borrowed(event);
            assert!(
                b.len() < SYSEX_CAPACITY,
                "{} bytes borrowed from a {SYSEX_CAPACITY}-byte buffer that also holds the ID",
                b.len()
            );
            assert!(b.iter().all(|&x| x < 0x80), "a status byte in {event:?}");
        }
    }
    match want {
        Expect::Error(e) => assert_eq!(got, Err(*e), "at the byte of {want:?}"),
        &Expect::Two {
            status,
            data: [lo, hi],
        } => {
            let value = u16::from(lo) | (u16::from(hi) << 7);
            let nibble = status & 0x0F;
            let event = match status & 0xF0 {
                p::ANALOG_MESSAGE => Event::Analog {
                    channel: nibble,
                    value,
                },
                p::DIGITAL_MESSAGE => Event::Digital {
                    port: nibble,
                    mask: (value & 0xFF) as u8,
                },
                _ => Event::Version {
                    major: lo,
                    minor: hi,
                },
            };
            if let Ok(Event::Analog { channel, value }) = got {
                assert!(channel <= 15 && value <= 0x3FFF, "{got:?}");
            }
            assert_eq!(got, Ok(event), "{want:?}");
        }
        Expect::Sysex { id, payload } => sysex(*id, &wire[payload.clone()], got),
    }
}

/// Checks the parser's reading of a well-framed sysex against its ID's layout (protocol.md
/// 2.6.0, i2c.md 2.6.0, AccelStepperFirmata as ConfigurableFirmata 2.10.1 sends it).
fn sysex(id: u8, payload: &[u8], got: Result<Event<'_>, FrameError>) {
    let malformed = Err(FrameError::Malformed {
        id,
        len: payload.len(),
    });
    let want = match (id, payload) {
        (p::REPORT_FIRMWARE, [major, minor, name @ ..]) => Ok(Event::Firmware {
            major: *major,
            minor: *minor,
            name,
        }),
        (p::CAPABILITY_RESPONSE, _) => Ok(Event::Capabilities(payload)),
        (p::ANALOG_MAPPING_RESPONSE, _) => Ok(Event::AnalogMapping(payload)),
        (p::PIN_STATE_RESPONSE, [pin, mode, state @ ..]) if (1..=3).contains(&state.len()) => {
            Ok(Event::PinState {
                pin: *pin,
                mode: *mode,
                state: state
                    .iter()
                    .rev()
                    .fold(0, |acc, &b| (acc << 7) | u32::from(b)),
            })
        }
        // The address of a reply is the 7-bit address the host asked for: its second byte
        // is 0, or the reply is not to a request of this host.
        (p::I2C_REPLY, [address, 0, lo, hi, data @ ..]) if data.len() % 2 == 0 => {
            Ok(Event::I2cReply {
                address: *address,
                register: u16::from(*lo) | (u16::from(*hi) << 7),
                data,
            })
        }
        (p::STRING_DATA, _) => Ok(Event::Text(payload)),
        (p::ACCELSTEPPER_DATA, &[command, device, b0, b1, b2, b3, b4])
            if command == p::ACCELSTEPPER_REPORT_POSITION
                || command == p::ACCELSTEPPER_MOVE_COMPLETE =>
        {
            // Sign and magnitude: 7 bits a byte, 3 of the fifth; the sign its bit 3.
            let magnitude = [b0, b1, b2, b3]
                .iter()
                .rev()
                .fold(u32::from(b4 & 0x07), |acc, &b| (acc << 7) | u32::from(b));
            let magnitude = i32::try_from(magnitude).expect("31 bits");
            let position = if b4 & 0x08 != 0 {
                -magnitude
            } else {
                magnitude
            };
            Ok(if command == p::ACCELSTEPPER_MOVE_COMPLETE {
                Event::StepperMoveComplete { device, position }
            } else {
                Event::StepperPosition { device, position }
            })
        }
        (p::ACCELSTEPPER_DATA, &[p::MULTISTEPPER_MOVE_COMPLETE, group]) => {
            Ok(Event::MultiStepperComplete { group })
        }
        (p::REPORT_FIRMWARE | p::PIN_STATE_RESPONSE | p::I2C_REPLY | p::ACCELSTEPPER_DATA, _) => {
            malformed
        }
        _ => Ok(Event::Sysex { id, payload }),
    };
    assert_eq!(got, want, "sysex {id:#04x} {payload:02x?}");
    if let Ok(Event::Capabilities(c)) = got {
        let pins = parse_capabilities(c);
        let bytes: usize = pins.iter().map(|pin| 1 + 2 * pin.modes.len()).sum();
        assert!(bytes <= c.len(), "{pins:?} from {c:02x?}");
    }
}

/// A report a board sends, made by firmata-host's encoders.
#[derive(Debug, Arbitrary)]
enum Report {
    Analog {
        channel: u8,
        value: u16,
    },
    Digital {
        port: u8,
        mask: u8,
    },
    Version {
        major: u8,
        minor: u8,
    },
    Firmware {
        major: u8,
        minor: u8,
        name: String,
    },
    /// Per pin, its (mode, resolution) pairs.
    Capabilities(Vec<Vec<(u8, u8)>>),
    AnalogMapping(Vec<u8>),
    /// `bytes` (1–3) is how many 7-bit bytes carry `state`.
    PinState {
        pin: u8,
        mode: u8,
        state: u32,
        bytes: u8,
    },
    I2cReply {
        address: u8,
        register: u16,
        data: Vec<u8>,
    },
    Text(String),
    Stepper {
        device: u8,
        position: i32,
        complete: bool,
    },
    MultiStepperComplete {
        group: u8,
    },
    /// A sysex this crate does not decode.
    Other {
        id: u8,
        payload: Vec<u8>,
    },
    /// A string of `len` copies of one character: a sysex around the parser's capacity.
    Long {
        fill: u8,
        len: u16,
    },
}

/// A sysex report's payload (after its ID) and ID.
fn sysex_bytes(id: u8, payload: impl IntoIterator<Item = u8>, out: &mut Vec<u8>) {
    out.extend([p::START_SYSEX, id]);
    out.extend(payload.into_iter().map(|b| b & 0x7F));
    out.push(p::END_SYSEX);
}

impl Report {
    /// The position a stepper report carries: every `i32` but `i32::MIN`, whose magnitude
    /// needs 32 bits (sign-magnitude has no form for it).
    fn position(position: i32) -> i32 {
        position.max(-i32::MAX)
    }

    fn encode(&self, out: &mut Vec<u8>) {
        match self {
            Report::Analog { channel, value } => p::encode_analog(out, *channel, *value),
            Report::Digital { port, mask } => p::encode_digital(out, *port, *mask),
            Report::Version { major, minor } => p::encode_version_report(out, *major, *minor),
            Report::Firmware { major, minor, name } => {
                p::encode_firmware_report(out, *major, *minor, name);
            }
            Report::Capabilities(pins) => {
                let bytes = pins.iter().flat_map(|modes| {
                    modes
                        .iter()
                        .flat_map(|&(m, r)| [m.min(0x7E), r])
                        .chain([0x7F])
                });
                sysex_bytes(p::CAPABILITY_RESPONSE, bytes, out);
            }
            Report::AnalogMapping(map) => {
                sysex_bytes(p::ANALOG_MAPPING_RESPONSE, map.iter().copied(), out);
            }
            Report::PinState {
                pin,
                mode,
                state,
                bytes,
            } => {
                let n = 1 + u32::from(bytes % 3);
                let state = (0..n).map(|k| ((state >> (7 * k)) & 0x7F) as u8);
                sysex_bytes(
                    p::PIN_STATE_RESPONSE,
                    [*pin, *mode].into_iter().chain(state),
                    out,
                );
            }
            Report::I2cReply {
                address,
                register,
                data,
            } => p::encode_i2c_reply(out, *address, *register, data),
            Report::Text(text) => p::encode_string(out, text),
            Report::Stepper {
                device,
                position,
                complete,
            } => p::encode_stepper_position(out, *device, Report::position(*position), *complete),
            Report::MultiStepperComplete { group } => sysex_bytes(
                p::ACCELSTEPPER_DATA,
                [p::MULTISTEPPER_MOVE_COMPLETE, *group],
                out,
            ),
            Report::Other { id, payload } => {
                // An ID this crate does not decode (0x00–0x5F and 0x7B–0x7F, some of them
                // optional features' IDs).
                let id = if id & 0x7F < 0x60 { id & 0x7F } else { 0x7B };
                sysex_bytes(id, payload.iter().copied(), out);
            }
            Report::Long { fill, len } => {
                let len = usize::from(*len) % (2 * SYSEX_CAPACITY);
                sysex_bytes(p::STRING_DATA, std::iter::repeat_n(*fill, len), out);
            }
        }
    }

    /// Checks that the parser read this report, arrived whole, as what was encoded.
    fn check(&self, wire: &[u8], got: Result<Event<'_>, FrameError>) {
        // A sysex longer than the buffer is an overflow, whatever its ID.
        if wire[0] == p::START_SYSEX && wire.len() - 2 > SYSEX_CAPACITY {
            assert_eq!(
                got,
                Err(FrameError::SysexOverflow { id: wire[1] }),
                "{self:?}"
            );
            return;
        }
        let fail = || panic!("{self:?} read as {got:?}");
        match (self, got) {
            (
                &Report::Analog { channel, value },
                Ok(Event::Analog {
                    channel: c,
                    value: v,
                }),
            ) => {
                assert_eq!((c, v), (channel & 0x0F, value & 0x3FFF));
            }
            (&Report::Digital { port, mask }, Ok(Event::Digital { port: q, mask: m })) => {
                assert_eq!((q, m), (port & 0x0F, mask));
            }
            (&Report::Version { major, minor }, Ok(Event::Version { major: a, minor: b })) => {
                assert_eq!((a, b), (major & 0x7F, minor & 0x7F));
            }
            (
                Report::Firmware { major, minor, name },
                Ok(Event::Firmware {
                    major: a,
                    minor: b,
                    name: n,
                }),
            ) => {
                assert_eq!((a, b), (major & 0x7F, minor & 0x7F));
                assert!(p::pairs(n).eq(name.bytes()), "{name:?} read as {n:02x?}");
                assert_eq!(n.len(), 2 * name.len());
            }
            (Report::Capabilities(pins), Ok(Event::Capabilities(c))) => {
                let read = parse_capabilities(c);
                assert_eq!(read.len(), pins.len());
                for (r, modes) in read.iter().zip(pins) {
                    let sent = modes
                        .iter()
                        .map(|&(m, res)| (p::PinMode::from_code(m.min(0x7E)), res & 0x7F));
                    assert!(r.modes.iter().copied().eq(sent), "{r:?} from {modes:?}");
                }
            }
            (Report::AnalogMapping(map), Ok(Event::AnalogMapping(m))) => {
                assert!(m.iter().copied().eq(map.iter().map(|b| b & 0x7F)));
            }
            (
                &Report::PinState {
                    pin,
                    mode,
                    state,
                    bytes,
                },
                Ok(Event::PinState {
                    pin: q,
                    mode: m,
                    state: s,
                }),
            ) => {
                let bits = 7 * (1 + u32::from(bytes % 3));
                assert_eq!(
                    (q, m, s),
                    (pin & 0x7F, mode & 0x7F, state & ((1 << bits) - 1))
                );
            }
            (
                Report::I2cReply {
                    address,
                    register,
                    data,
                },
                Ok(Event::I2cReply {
                    address: a,
                    register: r,
                    data: d,
                }),
            ) if *address <= 0x7F => {
                assert_eq!((a, r), (*address, register & 0x3FFF));
                assert!(
                    p::pairs(d).eq(data.iter().copied()),
                    "{data:02x?} read as {d:02x?}"
                );
            }
            // The host asks 7-bit addresses only: a reply from another is not to it.
            (Report::I2cReply { address, data, .. }, Err(FrameError::Malformed { id, len }))
                if *address > 0x7F =>
            {
                assert_eq!((id, len), (p::I2C_REPLY, 4 + 2 * data.len()));
            }
            (Report::Text(text), Ok(Event::Text(t))) => {
                assert!(p::pairs(t).eq(text.bytes()), "{text:?} read as {t:02x?}");
            }
            (
                &Report::Stepper {
                    device,
                    position,
                    complete: false,
                },
                Ok(Event::StepperPosition {
                    device: d,
                    position: at,
                }),
            )
            | (
                &Report::Stepper {
                    device,
                    position,
                    complete: true,
                },
                Ok(Event::StepperMoveComplete {
                    device: d,
                    position: at,
                }),
            ) => assert_eq!((d, at), (device & 0x7F, Report::position(position))),
            (
                &Report::MultiStepperComplete { group },
                Ok(Event::MultiStepperComplete { group: g }),
            ) => assert_eq!(g, group & 0x7F),
            (Report::Other { payload, .. }, Ok(Event::Sysex { payload: q, .. })) => {
                assert!(q.iter().copied().eq(payload.iter().map(|b| b & 0x7F)));
            }
            (&Report::Long { fill, .. }, Ok(Event::Text(t))) => {
                assert_eq!(t.len(), wire.len() - 3);
                assert!(t.iter().all(|&b| b == fill & 0x7F));
            }
            _ => fail(),
        }
    }
}

/// One part of a structured stream.
#[derive(Debug, Arbitrary)]
enum Part {
    /// A report, whole.
    Report(Report),
    /// A report cut after this many bytes (fewer than its length): bytes lost on the line.
    Cut(Report, u16),
    /// Bytes that are not Firmata: line noise, another sketch, another baud rate.
    Noise(Vec<u8>),
}

/// A structured input: the parts in order, and the chunk length they are read in.
#[derive(Debug, Arbitrary)]
struct Stream {
    parts: Vec<Part>,
    chunk: u8,
}

impl Stream {
    /// The stream's bytes, and every whole report with the place of its bytes.
    fn wire(&self) -> (Vec<u8>, Vec<(Range<usize>, &Report)>) {
        let mut wire = Vec::new();
        let mut whole = Vec::new();
        for part in &self.parts {
            let start = wire.len();
            match part {
                Part::Report(r) => {
                    r.encode(&mut wire);
                    whole.push((start..wire.len(), r));
                }
                Part::Cut(r, keep) => {
                    r.encode(&mut wire);
                    let len = wire.len() - start;
                    wire.truncate(start + usize::from(*keep) % len);
                }
                Part::Noise(bytes) => wire.extend_from_slice(bytes),
            }
        }
        (wire, whole)
    }
}

/// How many chunk boundaries a parser is carried over as a clone of itself: a clone allocates
/// the parser's buffer, and one at every few bytes would be most of a run's time.
const CLONES: usize = 16;

/// The host's Firmata parser on a board's byte stream.
///
/// Oracles:
/// - every report the parser makes, at the byte that completes it, is the one the stream's
///   framing gives by the parser's docs (`expected`), and it makes no other: a message's
///   fields are its data bytes (an analog value ≤ 16383 on channel ≤ 15), a sysex reads as its
///   ID's layout says or is `Malformed`, cut, stray, unknown and overlong input are the errors
///   the docs name, in order;
/// - [`parse_stream`] on the whole stream at once reports the same as a [`Parser`] given it
///   byte by byte and carried over each of the first `CLONES` chunk boundaries as a clone of
///   itself;
/// - a borrowed payload fits the parser's buffer with the ID (< [`SYSEX_CAPACITY`] bytes) and
///   holds 7-bit bytes only; every error displays;
/// - structured input: every report that arrives whole reads as what was encoded, whatever
///   noise or cut report came before it.
pub fn parser(data: &[u8]) {
    let data = crate::bounded(data);
    let [mode, rest @ ..] = data else {
        return;
    };
    let stream;
    let (wire, whole, chunk) = if *mode < 0x80 {
        (rest.to_vec(), Vec::new(), usize::from(*mode).max(1))
    } else {
        match Stream::arbitrary_take_rest(Unstructured::new(rest)) {
            Ok(s) => {
                stream = s;
                let (wire, whole) = stream.wire();
                (wire, whole, usize::from(stream.chunk).max(1))
            }
            Err(_) => return,
        }
    };
    let want = expected(&wire);

    let mut seen = 0;
    parse_stream(&wire, |got| {
        let (_, expect) = want
            .get(seen)
            .unwrap_or_else(|| panic!("report {seen} of {} expected: {got:?}", want.len()));
        check(&wire, expect, got);
        seen += 1;
    });
    assert_eq!(seen, want.len(), "parse_stream made too few reports");

    let mut parser = Parser::new();
    let mut want = want.iter().peekable();
    let mut whole = whole.into_iter().peekable();
    for (k, &b) in wire.iter().enumerate() {
        if k > 0 && k % chunk == 0 && k / chunk <= CLONES {
            parser = parser.clone();
        }
        let got = parser.push(b);
        let due = want.next_if(|(at, _)| *at == k);
        match (got, due) {
            (Some(got), Some((_, expect))) => {
                check(&wire, expect, got);
                if let Some((bytes, report)) = whole.next_if(|(r, _)| r.end == k + 1) {
                    report.check(&wire[bytes], got);
                }
            }
            (None, None) => {}
            (got, due) => panic!("at byte {k} ({b:#04x}): got {got:?}, expected {due:?}"),
        }
    }
    if let Some((_, report)) = whole.next() {
        panic!("{report:?} arrived whole and was not read");
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_second_reading_frames_as_the_parser_docs_say() {
        let got = expected(&[
            0x42, 0xF9, 2, 5, 0x03, 0xF0, 0x6C, 0xE0, 1, 0xF7, 0xF0, 0xF7,
        ]);
        assert_eq!(
            got,
            [
                (0, Expect::Error(FrameError::StrayData(0x42))),
                (
                    3,
                    Expect::Two {
                        status: 0xF9,
                        data: [2, 5]
                    }
                ),
                (4, Expect::Error(FrameError::StrayData(0x03))),
                (
                    7,
                    Expect::Error(FrameError::TruncatedSysex {
                        id: Some(0x6C),
                        len: 1
                    })
                ),
                // F7 cuts the analog message: only the cut is reported at it.
                (
                    9,
                    Expect::Error(FrameError::TruncatedMessage { command: 0xE0 })
                ),
                (
                    11,
                    Expect::Error(FrameError::TruncatedSysex { id: None, len: 0 })
                ),
            ]
        );
        assert_eq!(
            expected(&[0xF7, 0x01, 0xF0, 0x77, 1, 0xF7, 0x02]),
            [
                (0, Expect::Error(FrameError::UnknownCommand(0xF7))),
                (1, Expect::Error(FrameError::StrayData(1))),
                (
                    5,
                    Expect::Sysex {
                        id: 0x77,
                        payload: 4..5
                    }
                ),
                (6, Expect::Error(FrameError::StrayData(2))),
            ]
        );
    }

    /// The findings of `cargo xtask fuzz firmata` (`fuzz/regressions/firmata/`), each fixed in
    /// firmata-host's parser: an I2C reply whose address bytes say 0x264C, read as one from
    /// 0x4C; a string sysex past the buffer, cut by the next report, whose length was said
    /// to be the buffer's.
    #[test]
    fn the_findings_are_what_their_names_say() {
        let i2c = include_bytes!("../../../fuzz/regressions/firmata/i2c-reply-14-bit-address");
        assert_eq!(
            expected(&i2c[1..]),
            [(
                6,
                Expect::Sysex {
                    id: p::I2C_REPLY,
                    payload: 2..6
                }
            )]
        );
        parser(i2c);
        let cut = include_bytes!("../../../fuzz/regressions/firmata/cut-overlong-sysex");
        let stream = Stream::arbitrary_take_rest(Unstructured::new(&cut[1..])).expect("a stream");
        assert!(
            matches!(
                stream.parts[..],
                [Part::Cut(Report::Long { .. }, _), Part::Report(_)]
            ),
            "{stream:?}"
        );
        let (wire, _) = stream.wire();
        let first = expected(&wire)[0].1.clone();
        assert!(
            matches!(first, Expect::Error(FrameError::TruncatedSysex { len, .. }) if len > SYSEX_CAPACITY),
            "{first:?}"
        );
        parser(cut);
    }

    #[test]
    fn structured_streams_read_back() {
        let data: Vec<u8> = (0..4096u32)
            .map(|k| (k.wrapping_mul(2_654_435_761) >> 13) as u8)
            .collect();
        for start in 0..64 {
            let mut input = vec![0x80];
            input.extend_from_slice(&data[start * 7..]);
            parser(&input);
        }
    }
}
