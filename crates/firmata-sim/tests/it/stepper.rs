//! AccelStepperFirmata through the board: a move at speed and acceleration taking the time the
//! profile takes, position reports mid-move, relative moves, zero, stop.

use std::time::{Duration, Instant};

use firmata_host::{Board, Options, StepperConfig};
use firmata_sim::{AnalogInputs, ChipBus, FirmwareKind, SimBoard, SimConfig};

use crate::board;

#[test]
fn a_stepper_moves_at_its_speed_and_acceleration_and_reports_completion() {
    let (sim, mut board) = board(FirmwareKind::Configurable);
    board
        .stepper_config(0, &StepperConfig::driver(2, 3))
        .unwrap();
    board.stepper_set_speed(0, 400.0).unwrap();
    board.stepper_set_acceleration(0, 800.0).unwrap();
    let mark = board.mark();
    let start = Instant::now();
    board.stepper_to(0, 400).unwrap();
    // Mid-move the position is between start and target.
    board.poll(Duration::from_millis(20)).ok();
    let mid = board.stepper_position(0).unwrap();
    assert!((0..400).contains(&mid), "{mid}");
    let end = board
        .wait_stepper_complete(0, mark, Duration::from_secs(5))
        .unwrap();
    let took = start.elapsed();
    assert_eq!(end, 400);
    assert_eq!(sim.stepper_position(0), Some(400));
    // Trapezoid: 0.5 s up to 400 steps/s (100 steps), 200 steps at 400, 0.5 s down: 1.5 s.
    assert!(
        took >= Duration::from_millis(1400) && took < Duration::from_millis(1900),
        "{took:?}"
    );
    // Relative move back by 100, then zero where it stands.
    let mark = board.mark();
    board.stepper_step(0, -100).unwrap();
    assert_eq!(
        board
            .wait_stepper_complete(0, mark, Duration::from_secs(5))
            .unwrap(),
        300
    );
    assert_eq!(board.stepper_position(0).unwrap(), 300);
    board.stepper_zero(0).unwrap();
    assert_eq!(board.stepper_position(0).unwrap(), 0);
    // Negative positions travel sign-magnitude; stop ends a move early with a report.
    board.stepper_set_acceleration(0, 0.0).unwrap(); // full speed at once
    board.stepper_set_speed(0, 1000.0).unwrap();
    board.stepper_to(0, -100_000).unwrap();
    let mut pos = 0;
    while pos > -50 {
        pos = board.stepper_position(0).unwrap();
    }
    let stopped = board.stepper_stop(0).unwrap();
    assert!((-100_000..-49).contains(&stopped), "{stopped}");
    assert_eq!(
        board.stepper_position(0).unwrap(),
        stopped,
        "it stays where it stopped"
    );
}

#[test]
fn standard_firmata_has_no_steppers_and_says_nothing() {
    let (_sim, mut board) = board(FirmwareKind::Standard);
    board
        .stepper_config(0, &StepperConfig::driver(2, 3))
        .unwrap();
    let e = board.stepper_position(0).unwrap_err();
    assert!(
        e.to_string()
            .contains("no position report of stepper 0 within"),
        "{e}"
    );
}

/// A model whose A0 follows a stepper's shaft: 1 mV a step, counted from the steps it hears.
struct Shaft(i64);

impl AnalogInputs for Shaft {
    fn volts(&mut self, channel: u8, _now: Duration) -> f32 {
        if channel == 0 {
            self.0 as f32 * 1e-3
        } else {
            0.0
        }
    }

    fn stepper_moved(&mut self, device: u8, steps: i32, _now: Duration) {
        if device == 0 {
            self.0 += i64::from(steps);
        }
    }
}

#[test]
fn an_analog_model_hears_the_shaft_turn_and_not_the_counter_zeroed() {
    let config = SimConfig::default()
        .bus(ChipBus::empty())
        .analog(Shaft(0))
        .boot_delay(crate::BOOT);
    let sim = SimBoard::spawn(config).unwrap();
    let mut board = Board::open(sim.path(), &Options::default()).unwrap();
    board
        .stepper_config(0, &StepperConfig::driver(2, 3))
        .unwrap();
    board.stepper_set_acceleration(0, 0.0).unwrap();
    board.stepper_set_speed(0, 2000.0).unwrap();
    let mark = board.mark();
    board.stepper_to(0, 1000).unwrap();
    let timeout = Duration::from_secs(5);
    assert_eq!(board.wait_stepper_complete(0, mark, timeout).unwrap(), 1000);
    board.enable_analog(0).unwrap();
    // 1000 steps = 1 V = 205 counts (204.6 rounded), sampled after the move completed.
    assert_eq!(board.wait_analog(0, timeout).unwrap().counts, 205);
    // Zeroing the counter turns nothing; moving back 500 does.
    board.stepper_zero(0).unwrap();
    let mark = board.mark();
    board.stepper_to(0, -500).unwrap();
    assert_eq!(board.wait_stepper_complete(0, mark, timeout).unwrap(), -500);
    let deadline = Instant::now() + timeout;
    loop {
        let counts = board.wait_analog(0, timeout).unwrap().counts;
        if counts == 102 {
            break; // 0.5 V: 102.3 counts
        }
        assert!(Instant::now() < deadline, "A0 stuck at {counts} counts");
    }
}
