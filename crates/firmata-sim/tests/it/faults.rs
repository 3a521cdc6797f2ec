//! Bad input and lost boards: a garbled (truncated) reply, an unknown command, stray bytes, a
//! report for a pin never enabled, a refused sysex, an I2C NACK, requests too long for
//! Firmata, a board at another baud rate, and a board that vanishes mid-run.

use std::io::{BufRead, BufReader};
use std::process::{Command, Stdio};
use std::sync::mpsc;
use std::time::Duration;

use embedded_hal::i2c::{Error as _, ErrorKind as HalKind, I2c, NoAcknowledgeSource};
use firmata_host::parser::FrameError;
use firmata_host::{Board, ErrorKind, Options, protocol};
use firmata_sim::{Fault, FirmwareKind, SimBoard, SimConfig};

use crate::{BOOT, board};

#[test]
fn a_truncated_reply_is_a_garbled_error_naming_the_sysex() {
    let (sim, mut board) = board(FirmwareKind::Configurable);
    // Reports keep coming, so the bytes after the cut are the next analog message's.
    board.set_sampling_interval(5).unwrap();
    board.enable_analog(0).unwrap();
    sim.inject(Fault::TruncateNextReply);
    let e = board.capabilities().unwrap_err();
    match e.kind {
        ErrorKind::Garbled(FrameError::TruncatedSysex {
            id: Some(0x6C),
            len,
        }) => {
            assert!(len > 0)
        }
        ref other => panic!("{other:?}"),
    }
    assert!(
        e.to_string()
            .starts_with(&format!("board on {}", sim.path().display()))
    );
    assert!(e.to_string().contains("truncated sysex 0x6c"), "{e}");
    // The link recovers: the next query is answered.
    assert_eq!(board.capabilities().unwrap().len(), 20);
}

#[test]
fn unknown_commands_stray_bytes_and_unrequested_reports_are_counted_not_fatal() {
    let (sim, mut board) = board(FirmwareKind::Standard);
    let before = board.stats();
    let mut raw = vec![0xF2, 0x42, 0xA5, 0x01];
    // An analog report for A3, which this host never enabled.
    protocol::encode_analog(&mut raw, 3, 500);
    sim.inject(Fault::Raw(raw));
    assert_eq!(board.query_firmware().unwrap().name, "StandardFirmata");
    let after = board.stats();
    // 0xF2, then 0x42 stray; 0xA5 unknown, 0x01 stray.
    assert_eq!(after.frame_errors - before.frame_errors, 4);
    assert_eq!(after.unrequested_analog, 1);
    assert_eq!(board.analog(3).map(|r| r.counts), Some(500));
    assert_eq!(board.analog_enabled() & (1 << 3), 0);
}

#[test]
fn configurable_firmata_refuses_a_sysex_it_has_no_feature_for() {
    let (_sim, mut board) = board(FirmwareKind::Configurable);
    board.send_raw(&[0xF0, 0x0F, 0x01, 0xF7]).unwrap();
    assert_eq!(board.query_version().unwrap(), (2, 6));
    assert_eq!(board.last_text(), Some("Unhandled sysex command"));
}

#[test]
fn an_i2c_device_that_does_not_answer_is_a_nack_under_both_firmwares() {
    for kind in [FirmwareKind::Standard, FirmwareKind::Configurable] {
        let (_sim, mut board) = board(kind);
        let mut buf = [0u8; 2];
        let e = board
            .i2c_read(0x50, Some(0x00), true, &mut buf)
            .unwrap_err();
        assert!(
            matches!(
                e.kind,
                ErrorKind::I2cNack {
                    address: 0x50,
                    asked: 2,
                    got: 0
                }
            ),
            "{kind:?}: {e}"
        );
        assert_eq!(
            e.kind(),
            HalKind::NoAcknowledge(NoAcknowledgeSource::Unknown)
        );
        // Through embedded-hal: the same error; the bus goes on working.
        assert!(board.write_read(0x50, &[0], &mut buf).is_err());
        let mut who = [0u8; 1];
        board.write_read(0x68, &[0x75], &mut who).unwrap();
        assert_eq!(who[0], 0x03, "ICM-20789 WHO_AM_I");
    }
}

#[test]
fn transfers_firmata_cannot_carry_are_refused_before_anything_is_sent() {
    let (sim, mut board) = board(FirmwareKind::Standard);
    let sent = sim.bytes().0;
    let mut big = [0u8; 33];
    let e = board.read(0x77, &mut big).unwrap_err();
    assert!(
        matches!(
            e.kind,
            ErrorKind::I2cTooLong {
                what: "read",
                len: 33,
                max: 32
            }
        ),
        "{e}"
    );
    let e = board.write(0x77, &[0u8; 31]).unwrap_err();
    assert!(
        matches!(
            e.kind,
            ErrorKind::I2cTooLong {
                what: "write",
                len: 31,
                max: 30
            }
        ),
        "{e}"
    );
    let e = board.i2c_write(0x80, &[1]).unwrap_err();
    assert!(matches!(e.kind, ErrorKind::I2cUnsupported(_)), "{e}");
    let e = board.stepper_to(0, 1 << 28).unwrap_err();
    assert!(matches!(e.kind, ErrorKind::OutOfRange { .. }), "{e}");
    assert_eq!(board.query_version().unwrap(), (2, 5));
    // Only the version query went out.
    assert_eq!(sim.bytes().0 - sent, 1);
}

#[test]
fn a_client_at_another_baud_rate_gets_garbage_and_a_typed_error() {
    let sim = SimBoard::spawn(SimConfig::default().boot_delay(BOOT)).unwrap();
    let options = Options {
        baud: 115_200,
        boot_wait: Duration::from_millis(400),
        reply_timeout: Duration::from_millis(300),
        ..Options::default()
    };
    let e = Board::open(sim.path(), &options).unwrap_err();
    assert!(
        matches!(e.kind, ErrorKind::NotFirmata { baud: 115_200, .. }),
        "{e}"
    );
    assert!(e.to_string().contains("another baud rate"), "{e}");
    assert_eq!(sim.client_baud(), Some(115_200));
    crate::wait_closed(&sim);
    // At the right rate it answers.
    let board = Board::open(sim.path(), &Options::default()).unwrap();
    assert_eq!(board.protocol_version(), Some((2, 6)));
}

#[test]
fn a_board_that_vanishes_mid_run_is_a_disconnected_error() {
    // In process: the simulator's end closes.
    let (sim, mut board) = board(FirmwareKind::Standard);
    board.enable_analog(0).unwrap();
    drop(sim);
    let e = board.wait_analog(0, Duration::from_secs(2)).unwrap_err();
    assert!(matches!(e.kind, ErrorKind::Disconnected), "{e}");

    // Another process, killed.
    let mut child = Command::new(env!("CARGO_BIN_EXE_firmata-sim"))
        .args(["--boot-ms", "100"])
        .stdout(Stdio::piped())
        .spawn()
        .expect("spawn firmata-sim");
    let _guard = crate::KillOnDrop(child.id().to_string());
    let stdout = child.stdout.take().expect("piped");
    let (tx, rx) = mpsc::channel();
    std::thread::spawn(move || {
        let mut line = String::new();
        let _ = BufReader::new(stdout).read_line(&mut line);
        let _ = tx.send(line);
    });
    let line = rx
        .recv_timeout(Duration::from_secs(10))
        .expect("the pty's path");
    let mut board = Board::open(line.trim_end(), &Options::default()).unwrap();
    board.set_sampling_interval(5).unwrap();
    board.enable_analog(0).unwrap();
    child.kill().expect("SIGKILL");
    let _ = child.wait();
    let e = loop {
        match board.wait_analog(0, Duration::from_secs(2)) {
            Ok(_) => continue, // reports already on the line
            Err(e) => break e,
        }
    };
    assert!(matches!(e.kind, ErrorKind::Disconnected), "{e}");
    assert!(e.to_string().contains(line.trim_end()), "{e}");
}
