//! handstack's grasp hold (`handstack::runs::grasp::hold`) and its endings in simulated time,
//! cycle by cycle: a fault ends the hold in the cycle it is seen (unless the scene's recovery
//! clears it), a stop before the next cycle, and the hand gets its end action either way. The
//! servos are `ServoHand` over Protocol 2.0 to `dxl-sim`'s bus on a pty, in this process so a
//! test injects a fault at the cycle of its choosing; the fingertip three MS5611 chip models
//! behind the real driver, on the loop's simulated clock.

use baro_drivers::sim::{Conditions, Ms5611Sim, SimClock};
use baro_drivers::{Address, I2cInterface, Ms5611, Osr, Ready, Scheduler};
use dxl_sim::{Fault, REPLY_LATENCY, SimBus, SimConfig};
use hand_control::ServoHand;
use hand_control::grasp_loop::LoopConfig;
use hand_traits::{PressureFrame, TactileSource};
use handstack::runs::grasp::{HoldFor, Plan, hold};
use handstack::scene::experiment::Recover;
use handstack::stop::Stop;
use handstack::{Ending, RunError};
use std::time::Duration;

type Chip = Ms5611<I2cInterface<Ms5611Sim<fn(u64) -> Conditions>>, Ready>;

/// Pressed by 2 mbar from 0.2 s of simulated time.
fn pressed(t_ns: u64) -> Conditions {
    Conditions {
        pressure_mbar: if t_ns >= 200_000_000 { 1002.0 } else { 1000.0 },
        temperature_celsius: 25.0,
    }
}

/// Three chip models read by the driver; `at_frame(n)` runs before frame `n` is read, so a
/// test acts on the world at a cycle of its choosing.
struct Tip<'a> {
    chips: Vec<Chip>,
    scheduler: Scheduler,
    clock: SimClock,
    frames: u64,
    at_frame: Box<dyn FnMut(u64) + 'a>,
}

impl<'a> Tip<'a> {
    fn new(clock: &SimClock, at_frame: impl FnMut(u64) + 'a) -> Tip<'a> {
        let mut delay = clock.delay();
        let chips = (0..3)
            .map(|_| {
                let chip = Ms5611Sim::new(pressed as fn(u64) -> Conditions, clock.clone())
                    .with_noise(false);
                Ms5611::new_with_i2c(chip, Address::CsbLow)
                    .init(&mut delay)
                    .map_err(|e| e.error)
                    .expect("chip model")
            })
            .collect();
        Tip {
            chips,
            scheduler: Scheduler::new(Osr::Osr256),
            clock: clock.clone(),
            frames: 0,
            at_frame: Box::new(at_frame),
        }
    }
}

impl TactileSource for Tip<'_> {
    type Frame = PressureFrame<3>;
    type Error = RunError;
    fn read_frame(&mut self) -> Result<PressureFrame<3>, RunError> {
        (self.at_frame)(self.frames);
        self.frames += 1;
        let mut out = [baro_drivers::Measurement {
            temperature_centi_celsius: 0,
            pressure_pa: 0,
        }; 3];
        self.scheduler
            .sample_all(&mut self.chips, &mut self.clock.delay(), &mut out)
            .map_err(|e| RunError::Device {
                device: "sensors.fingertip",
                reason: e.error.to_string(),
            })?;
        Ok(PressureFrame {
            t_us: self.clock.now_us(),
            pressure_pa: out.map(|m| m.pressure_pa as f32),
        })
    }
}

/// The hold (`hold_s` from the first command), with `recover`, ended by `stop`; before each
/// frame the servos' time is moved on by a cycle (10 ms, so they move as fast as the loop runs)
/// and `at_frame` acts on the bus. Returns the result and how many frames the loop read.
fn run(
    hold_s: f64,
    recover: Option<Recover>,
    stop: &Stop,
    at_frame: impl FnMut(&mut SimBus, u64),
) -> (Result<String, RunError>, u64, SimBus) {
    let (bus, port) = SimBus::spawn(SimConfig::with_ids(&[1, 2])).expect("pty");
    let mut hand = ServoHand::with_reply_latency(port, &[1, 2], REPLY_LATENCY).expect("servos");
    hand.set_torque(true).expect("torque on");
    let clock = SimClock::new();
    let frames = std::cell::Cell::new(0);
    let bus = std::cell::RefCell::new(bus);
    let mut at_frame = at_frame;
    let result = {
        let tip = Tip::new(&clock, |n| {
            frames.set(n + 1);
            let mut bus = bus.borrow_mut();
            bus.advance(Duration::from_millis(10))
                .expect("the bus runs");
            at_frame(&mut bus, n);
        });
        let plan = Plan {
            hold: HoldFor::FirstCommand(hold_s),
            recover,
            stop,
            hand: "servo bus (test)",
            record: None,
        };
        let config = LoopConfig {
            band: hand_control::grasp_loop::TorqueBand::new(250, 320).expect("band"),
            ..LoopConfig::new()
        };
        hold(tip, hand, clock.clone(), config, &plan).map(|held| held.left)
    };
    (result, frames.get(), bus.into_inner())
}

/// Whether each servo has torque on, once the bus has run every byte sent (the torque off is
/// a broadcast: nothing answers it to wait for).
fn torque_on(bus: &mut SimBus) -> [bool; 2] {
    bus.sync().expect("the bus runs");
    [1, 2].map(|id| bus.with_servo(id, |s| s.torque_enabled()).expect("servo"))
}

#[test]
fn a_servo_that_stops_answering_ends_the_hold_in_that_cycle() {
    let stop = Stop::new();
    let (result, frames, mut bus) = run(5.0, None, &stop, |bus, n| {
        if n == 50 {
            bus.inject(2, Fault::Mute);
        }
    });
    // Frame 50 was the fault's cycle: no frame after it.
    assert_eq!(frames, 51);
    match result {
        Err(
            ref e @ RunError::Ended {
                ending: Ending::Fault,
                ..
            },
        ) => {
            let text = e.to_string();
            assert!(
                text.starts_with("hand: servo bus (test): ")
                    && text.contains("servo 2: no answer (timeout) at 0.50 s of the grasp; hand "),
                "{text}"
            );
        }
        other => panic!("expected a fault ending, got {other:?}"),
    }
    // Servo 1 still answers: it got the end action (release, then torque off).
    assert!(!torque_on(&mut bus)[0]);
}

#[test]
fn a_stop_ends_the_hold_before_the_next_cycle_with_the_end_action() {
    let stop = Stop::new();
    let asked = stop.clone();
    let (result, frames, mut bus) = run(5.0, None, &stop, |_, n| {
        if n == 40 {
            asked.set();
        }
    });
    assert_eq!(frames, 41, "a cycle ran after the stop");
    match result {
        Err(ref e @ RunError::Ended { ending, .. }) => {
            assert_eq!(ending, Ending::Stopped(handstack::stop::StopReason::Asked));
            let text = e.to_string();
            assert!(
                text.starts_with("stopped by a stop request at 0.40 s of the grasp; hand "),
                "{text}"
            );
            assert!(text.ends_with("then torque off"), "{text}");
        }
        other => panic!("expected a stop, got {other:?}"),
    }
    assert_eq!(torque_on(&mut bus), [false, false]);
}

#[test]
fn an_overload_ends_the_hold_unless_the_scene_recovers_from_it() {
    let overload = |bus: &mut SimBus, n: u64| {
        if n == 60 {
            bus.with_servo(1, |s| s.raise_hardware_error(0x20));
        }
    };
    let (result, frames, _) = run(2.0, None, &Stop::new(), overload);
    assert_eq!(frames, 61);
    let text = result.expect_err("a fault").to_string();
    assert!(
        text.contains("servo hardware error: overload at 0.60 s"),
        "{text}"
    );
    // With a recovery: rebooted after its cooldown, the hold runs to its end.
    let recover = Recover {
        attempts: 2,
        within_s: 3.0,
    };
    let (result, frames, mut bus) = run(4.0, Some(recover), &Stop::new(), overload);
    let left = result.unwrap_or_else(|e| panic!("{e}"));
    assert!(frames > 400, "{frames}");
    assert!(left.ends_with("then torque off"), "{left}");
    assert_eq!(torque_on(&mut bus), [false, false]);
}

/// A recovery that does not come in time, or runs out of reboots, ends the run saying which.
#[test]
fn a_recovery_that_runs_out_of_time_or_reboots_ends_the_run() {
    let once = |bus: &mut SimBus, n: u64| {
        if n == 60 {
            bus.with_servo(1, |s| s.raise_hardware_error(0x20));
        }
    };
    // The reboot comes after 0.5 s in the safe state: later than 0.2 s allows.
    let hurried = Recover {
        attempts: 2,
        within_s: 0.2,
    };
    let (result, _, mut bus) = run(4.0, Some(hurried), &Stop::new(), once);
    let text = result.expect_err("not recovered in time").to_string();
    assert!(
        text.contains("not recovered within 0.2 s of its fault"),
        "{text}"
    );
    assert_eq!(torque_on(&mut bus), [false, false]);
    // Overloaded again after its one reboot: the reboots are used up.
    let twice = |bus: &mut SimBus, n: u64| {
        if n == 60 || n == 200 {
            bus.with_servo(1, |s| s.raise_hardware_error(0x20));
        }
    };
    let one = Recover {
        attempts: 1,
        within_s: 3.0,
    };
    let (result, frames, mut bus) = run(4.0, Some(one), &Stop::new(), twice);
    let text = result.expect_err("reboots used up").to_string();
    assert!(
        text.contains("still faulted after 1 recovery reboots"),
        "{text} after {frames} frames"
    );
    assert!(frames < 400, "{frames}");
    assert_eq!(torque_on(&mut bus), [false, false]);
}

#[test]
fn a_panic_in_a_hold_cycle_ends_it_with_the_end_action() {
    let (mut bus, port) = SimBus::spawn(SimConfig::with_ids(&[1, 2])).expect("pty");
    let mut hand = ServoHand::with_reply_latency(port, &[1, 2], REPLY_LATENCY).expect("servos");
    hand.set_torque(true).expect("torque on");
    let clock = SimClock::new();
    let stop = Stop::new();
    let tip = Tip::new(&clock, |n| {
        // A bug in the run's own code, mid-grasp.
        assert!(n < 30, "a bug");
    });
    let plan = Plan {
        hold: HoldFor::FirstCommand(5.0),
        recover: None,
        stop: &stop,
        hand: "servo bus (test)",
        record: None,
    };
    // The cycle's panic is caught: the hand gets the configuration's end action (release,
    // then torque off), and the run ends as a bug.
    let err = hold(tip, hand, clock.clone(), LoopConfig::new(), &plan)
        .map(|held| held.left)
        .expect_err("the panic ends the hold");
    assert_eq!(err.exit_code(), handstack::error::EXIT_BUG, "{err}");
    let text = err.to_string();
    assert!(
        text.contains("a bug in handstack: a bug") && text.contains("then torque off"),
        "{text}"
    );
    assert_eq!(torque_on(&mut bus), [false, false]);
}
