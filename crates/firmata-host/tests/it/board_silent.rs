//! `Board` on a line where nothing answers, or something other than Firmata does: one end of a
//! pty pair is the board's port, the test writes the other end itself.

use std::time::{Duration, Instant};

use firmata_host::{Board, ErrorKind, Options};
use serial2::SerialPort;

fn quick() -> Options {
    Options {
        boot_wait: Duration::from_millis(100),
        reply_timeout: Duration::from_millis(100),
        ..Options::default()
    }
}

#[test]
fn a_silent_port_times_out_after_asking() {
    let (far, near) = SerialPort::pair().unwrap();
    let start = Instant::now();
    let e = Board::with_port(near, "pty".into(), &quick()).unwrap_err();
    assert!(matches!(e.kind, ErrorKind::Timeout { .. }), "{e}");
    assert_eq!(
        e.to_string(),
        "board on pty: no protocol version report within 100 ms"
    );
    assert!(start.elapsed() >= Duration::from_millis(200));
    // It asked after the boot wait: the version and firmware queries.
    let mut buf = [0u8; 16];
    let n = far.read(&mut buf).unwrap();
    assert_eq!(&buf[..n], [0xF9, 0xF0, 0x79, 0xF7]);
}

#[test]
fn a_sketch_printing_text_is_not_firmata() {
    let (far, near) = SerialPort::pair().unwrap();
    // The sketch answers whatever it receives (the host's queries) with a line of text.
    let sketch = std::thread::spawn(move || {
        let mut buf = [0u8; 16];
        let _ = far.read(&mut buf).unwrap();
        far.write_all(b"Hello from setup()\r\n").unwrap();
        far
    });
    let e = Board::with_port(near, "pty".into(), &quick()).unwrap_err();
    drop(sketch.join().unwrap());
    match &e.kind {
        ErrorKind::NotFirmata {
            baud: 57_600,
            bytes: 20,
            sample,
        } => {
            assert!(sample.contains("Hello from setup()"), "{sample}")
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn a_board_that_answers_the_query_opens_without_a_reset() {
    let (far, near) = SerialPort::pair().unwrap();
    let answer = std::thread::spawn(move || {
        let mut buf = [0u8; 16];
        let mut got = Vec::new();
        while got.len() < 4 {
            let n = far.read(&mut buf).unwrap();
            got.extend_from_slice(&buf[..n]);
        }
        let mut out = Vec::new();
        firmata_host::protocol::encode_version_report(&mut out, 2, 5);
        firmata_host::protocol::encode_firmware_report(&mut out, 2, 5, "Blink");
        far.write_all(&out).unwrap();
        far
    });
    let board = Board::with_port(near, "pty".into(), &quick()).unwrap();
    assert_eq!(board.protocol_version(), Some((2, 5)));
    assert_eq!(board.firmware().unwrap().name, "Blink");
    drop(answer.join().unwrap());
}
