//! `firmata-host`'s `Board` against the simulated board: the reset on open, the queries, pin
//! modes, analog and digital reporting with replies interleaved among reports.

use std::time::{Duration, Instant};

use firmata_host::{Board, Options, PinMode};
use firmata_sim::{BoardKind, FirmwareKind, SimBoard, SimConfig};

use crate::{BOOT, board};

#[test]
fn the_board_resets_on_each_open_and_reports_version_and_firmware() {
    for (kind, version, name, minor) in [
        (FirmwareKind::Standard, (2, 5), "StandardFirmata", 5),
        (
            FirmwareKind::Configurable,
            (2, 6),
            "ConfigurableFirmata",
            10,
        ),
    ] {
        let boot = Duration::from_millis(400);
        let sim = SimBoard::spawn(SimConfig::default().firmware(kind).boot_delay(boot)).unwrap();
        assert_eq!(sim.boots(), 0, "no reset before the port opens");
        let start = Instant::now();
        let mut board = Board::open(sim.path(), &Options::default()).unwrap();
        let waited = start.elapsed();
        // The version came unasked after the boot delay: open waited for it, no longer.
        assert!(waited >= boot, "{waited:?}");
        assert!(waited < boot + Duration::from_millis(400), "{waited:?}");
        assert_eq!(board.protocol_version(), Some(version));
        let fw = board.firmware().expect("firmware report at boot").clone();
        assert_eq!((fw.name.as_str(), fw.major, fw.minor), (name, 2, minor));
        assert_eq!(sim.boots(), 1);
        // Asked again, without a reset.
        assert_eq!(board.query_version().unwrap(), version);
        assert_eq!(board.query_firmware().unwrap(), fw);
        drop(board);
        crate::wait_closed(&sim);
        // The next open resets the board again.
        let board = Board::open(sim.path(), &Options::default()).unwrap();
        assert_eq!(board.protocol_version(), Some(version));
        assert_eq!(sim.boots(), 2);
    }
}

#[test]
fn capability_and_analog_mapping_of_an_uno_and_a_mega() {
    for (kind, pins, first_analog, channels, sda) in [
        (BoardKind::Uno, 20, 14, 6, 18),
        (BoardKind::Mega2560, 70, 54, 16, 20),
    ] {
        let sim = SimBoard::spawn(SimConfig::default().board(kind).boot_delay(BOOT)).unwrap();
        let mut board = Board::open(sim.path(), &Options::default()).unwrap();
        let caps = board.capabilities().unwrap().to_vec();
        assert_eq!(caps.len(), pins, "{kind:?}");
        assert!(
            caps[0].modes.is_empty() && caps[1].modes.is_empty(),
            "RX / TX"
        );
        assert_eq!(caps[first_analog].resolution(PinMode::Analog), Some(10));
        assert_eq!(caps[sda].resolution(PinMode::I2c), Some(1));
        assert_eq!(caps[3].resolution(PinMode::Pwm), Some(8));
        assert_eq!(caps[2].resolution(PinMode::Stepper), Some(21));
        assert_eq!(caps[2].resolution(PinMode::Analog), None);
        let map = board.analog_mapping().unwrap().to_vec();
        assert_eq!(map.len(), pins);
        for (pin, &ch) in map.iter().enumerate() {
            if pin >= first_analog {
                assert_eq!(usize::from(ch), pin - first_analog);
            } else {
                assert_eq!(ch, 127, "pin {pin}");
            }
        }
        assert_eq!(map.iter().filter(|c| **c != 127).count(), channels);
    }
}

#[test]
fn analog_reports_come_every_sampling_interval_and_replies_arrive_among_them() {
    let (sim, mut board) = board(FirmwareKind::Configurable);
    sim.volts().set(0, 1.25);
    sim.volts().set(1, 3.3);
    board.set_sampling_interval(10).unwrap();
    let a0 = board.enable_analog(0).unwrap();
    assert_eq!(a0.counts, 256);
    assert!((a0.volts - 1.25).abs() < 5.0 / 1023.0, "{}", a0.volts);
    let a1 = board.enable_analog(1).unwrap();
    assert_eq!(a1.counts, 675); // 3.3 V
    // Count A0's reports over 300 ms while asking for things: every reply is found among them.
    let start = Instant::now();
    let mut reports = 0;
    let mut queries = 0;
    while start.elapsed() < Duration::from_millis(300) {
        board.wait_analog(0, Duration::from_millis(100)).unwrap();
        reports += 1;
        if reports % 5 == 0 {
            assert_eq!(board.query_firmware().unwrap().name, "ConfigurableFirmata");
            assert_eq!(board.capabilities().unwrap().len(), 20);
            queries += 1;
        }
    }
    // StandardFirmata's `loop()` samples when more than the interval has passed: every 10–11 ms.
    assert!(
        (20..=32).contains(&reports),
        "{reports} reports in 300 ms at 10 ms"
    );
    assert!(queries >= 4);
    assert_eq!(board.stats().frame_errors, 0);
    // A voltage change shows in the next report.
    sim.volts().set(0, 5.0);
    let deadline = Instant::now() + Duration::from_secs(1);
    while board
        .wait_analog(0, Duration::from_millis(100))
        .unwrap()
        .counts
        != 1023
    {
        assert!(Instant::now() < deadline, "A0 never read 5 V");
    }
    // Reporting off: the channel's value is dropped, and after a report already on the line,
    // no report comes.
    board.report_analog(0, false).unwrap();
    assert!(board.analog(0).is_none());
    let _ = board.wait_analog(0, Duration::from_millis(30));
    assert!(board.wait_analog(0, Duration::from_millis(60)).is_err());
}

#[test]
fn digital_ports_report_on_enable_and_pins_take_their_modes() {
    let (_sim, mut board) = board(FirmwareKind::Standard);
    board.set_pin_mode(2, PinMode::InputPullup).unwrap();
    board.set_pin_mode(4, PinMode::Output).unwrap();
    board.digital_write(4, true).unwrap();
    board.report_digital(0, true).unwrap();
    let deadline = Instant::now() + Duration::from_secs(1);
    while board.digital_port(0).is_none() {
        assert!(Instant::now() < deadline, "no digital report");
        board.poll(Duration::from_millis(50)).unwrap();
    }
    // Pin 2 pulled up, pin 4 driven high.
    assert_eq!(board.digital_port(0), Some(0b0001_0100));
}
