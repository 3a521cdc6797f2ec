//! Faults in the closed loop: overload, a lost status packet, a corrupted
//! CRC, a servo that stops answering, an out-of-range command → a typed error, the safe state
//! in the same cycle, nothing panics, and the log keeps every cycle.
//!
//! The actuator is the Dynamixel driver on the simulated Protocol 2.0 bus (see `support`); the
//! overload is the servo's own (seed 000 §7: full torque on a stiff object), the wire faults are
//! injected on the bus.

use crate::common;

use paper_experiments::grasp_rig as support;

use hand_control::Error;
use hand_control::grasp_loop::{FaultKind, LoopFault, Mode, Recovery, TorqueBand};
use hand_sim::grasp::{ObjectKind, ObjectParams, RigParams};
use hand_traits::{Faults, SafeAction};
use support::{Injected, Injection, SimLoop};

/// Back to grasping as soon as the fault clears, without a reboot.
const RESUME: Recovery = Recovery::Automatic {
    cooldown_us: 0,
    max_reboots: 0,
};

fn cube() -> ObjectParams {
    ObjectParams::table5(ObjectKind::Cube, &RigParams::default()).expect("cube")
}

fn cube_band() -> TorqueBand {
    TorqueBand::new(80, 400).expect("Table 5 cube")
}

/// Every 10 ms tick up to `until_s` is in the log, in order. The grid starts where the
/// fingertip's start-up (PROM reads over SPI) left the clock.
fn every_cycle_logged(l: &SimLoop, until_s: f64) {
    let t0 = l.log()[0].t_us;
    let n = ((until_s * 1e6) as u64 - t0).div_ceil(10_000) as usize;
    assert_eq!(l.log().len(), n);
    common::ticks_in_order(l.log());
}

#[test]
fn overload_at_full_torque_goes_torque_off_in_the_same_cycle() {
    // §7: "after setting the torque to 100 %, the current continued to increase so that the
    // grasping action was released". The full band lets the policy reach 1023 on a stiff cube.
    let (w, hand) = support::world(cube(), 7).expect("cube world");
    let mut cfg = support::config(TorqueBand::FULL);
    cfg.target_pressure_pa = 5_000.0; // unreachable: the policy saturates at full torque
    cfg.safe_action = SafeAction::TorqueOff;
    let mut l = support::grasp_loop(&w, hand, cfg).expect("valid config");
    l.run_until(6_000_000);
    every_cycle_logged(&l, 6.0);
    let i = common::safe_on_first_fault(
        l.log(),
        FaultKind::Hardware(Faults::OVERLOAD),
        SafeAction::TorqueOff,
    );
    // The cycle before was grasping above the servo's 90 % overload threshold.
    let before = &l.log()[i - 1];
    assert_eq!(before.mode, Mode::Grasp);
    assert!(before.torque_raw.expect("sent") > 920, "{before:?}");
    assert!(matches!(
        l.events()[0].fault,
        LoopFault::Hardware(f) if f.contains(Faults::OVERLOAD)
    ));
    // The fault shows in the state read after that cycle's command; nothing is sent after it,
    // and every later cycle is still logged, in the safe state.
    assert!(l.log()[i..].iter().all(|s| s.mode == Mode::Safe));
    assert!(l.log()[i + 1..].iter().all(|s| s.torque_raw.is_none()));
    assert!(!w.borrow().state().torque_enabled);
}

#[test]
fn overload_recovers_by_reboot_once_the_load_is_gone() {
    let (w, hand) = support::world(cube(), 7).expect("cube world");
    // Lifted before the overload can latch (≥ 1 s at ≥ 90 % load), so torque-off drops the cube
    // (§7's release) and the load is really gone when the loop reboots.
    w.borrow().lift_at(0.5);
    let mut cfg = support::config(TorqueBand::FULL);
    cfg.target_pressure_pa = 5_000.0;
    cfg.safe_action = SafeAction::TorqueOff;
    cfg.recovery = Recovery::Automatic {
        cooldown_us: 500_000,
        max_reboots: 1,
    };
    let mut l = support::grasp_loop(&w, hand, cfg).expect("valid config");
    l.run_until(12_000_000);
    let i = common::first_fault(l.log());
    let reboot = l.log().iter().position(|s| s.rebooted).expect("rebooted");
    // Not before the cool-down, and only with the load released.
    assert!(l.log()[reboot].t_us - l.log()[i].t_us >= 500_000);
    assert!(l.log()[reboot].state.expect("state").load_fraction.abs() <= 0.05);
    // Back to grasping the cycle after. The cube fell when the torque went off (§7's release),
    // so the hand now closes on nothing and does not overload again.
    assert_eq!(l.log()[reboot + 1].mode, Mode::Grasp);
    assert_eq!(
        (l.reboots(), l.mode()),
        (1, Mode::Grasp),
        "{:?}",
        l.events()
    );
    assert!(w.borrow().state().dropped);
    assert!(l.log()[reboot + 1..].iter().all(|s| s.fault.is_none()));
}

/// Runs a held cube with `kind` injected in `from_s..until_s`; returns the loop.
fn with_injection(kind: Injected, from_s: f64, until_s: f64, cfg_recovery: Recovery) -> SimLoop {
    let (w, hand) = support::world(cube(), 7).expect("cube world");
    w.borrow_mut().injections.push(Injection {
        from_s,
        until_s,
        kind,
    });
    let mut cfg = support::config(cube_band());
    cfg.recovery = cfg_recovery;
    let mut l = support::grasp_loop(&w, hand, cfg).expect("valid config");
    l.run_until(8_000_000);
    every_cycle_logged(&l, 8.0);
    // The cube is still held: the safe state holds the last safe effort.
    let s = w.borrow().state();
    assert!(!s.dropped && !s.damaged && s.slip_m < 1e-4, "{s:?}");
    l
}

#[test]
fn lost_status_packet_holds_then_resumes() {
    // One cycle's exchange lost (the injection window covers one 10 ms tick).
    let l = with_injection(Injected::Silent, 4.0, 4.01, RESUME);
    // A sync write needs no answer: the cycle's state read is what times out.
    let i = common::safe_on_first_fault(l.log(), FaultKind::State, SafeAction::HoldLastSafeEffort);
    assert!((4_000_000..4_010_000).contains(&l.log()[i].t_us));
    assert!(matches!(
        l.events()[0].fault,
        LoopFault::State(Error::Timeout { .. })
    ));
    // The next cycle answers again: grasping resumes, the rest is clean.
    assert_eq!(l.log()[i + 1].mode, Mode::Grasp);
    assert!(l.log()[i + 1..].iter().all(|s| s.fault.is_none()));
    assert_eq!(l.mode(), Mode::Grasp);
}

#[test]
fn corrupted_crc_is_a_typed_fault_and_safe() {
    let l = with_injection(Injected::Crc, 4.0, 4.01, Recovery::Manual);
    let _ = common::safe_on_first_fault(l.log(), FaultKind::State, SafeAction::HoldLastSafeEffort);
    assert!(matches!(
        l.events()[0].fault,
        LoopFault::State(Error::Crc { .. })
    ));
    // Manual recovery: it stays safe, nothing more is commanded.
    assert_eq!(l.mode(), Mode::Safe);
    // The fault's own cycle sent its sync write before the state read failed; nothing after.
    let i = common::first_fault(l.log());
    assert!(l.log()[i + 1..].iter().all(|s| s.torque_raw.is_none()));
}

#[test]
fn servo_that_stops_answering_keeps_the_loop_safe_until_it_answers() {
    // 0.1 s of silence: each cycle waits out the driver's reply allowance
    // (`dxl_sim::REPLY_LATENCY` of wall time), so the window is kept short.
    let l = with_injection(Injected::Silent, 4.0, 4.1, RESUME);
    let i = common::first_fault(l.log());
    // Silent from 4 s: every cycle logged with the fault and in the safe state.
    let silent = &l.log()[i..i + 10];
    assert!(
        silent
            .iter()
            .all(|s| s.mode == Mode::Safe && s.fault.is_some())
    );
    // No state read succeeds; no command after the first silent cycle's (sent before its
    // read timed out). The safe stop (hold the last safe effort) is a broadcast sync write: it
    // needs no answer, so it goes out in the fault's cycle and does not fail.
    assert!(silent.iter().all(|s| s.state.is_none()));
    assert!(silent[1..].iter().all(|s| s.torque_raw.is_none()));
    assert_eq!(silent[0].safe_action, Some(SafeAction::HoldLastSafeEffort));
    assert!(
        !l.events()
            .iter()
            .any(|e| matches!(e.fault, LoopFault::SafeStop(_)))
    );
    assert!(l.events().len() < 10, "{} events", l.events().len());
    // From 6 s it answers: safe stop confirmed, then grasping again.
    assert_eq!(l.mode(), Mode::Grasp);
}

#[test]
fn out_of_range_goal_refused_by_the_loop_or_by_the_driver_before_sending() {
    let (w, hand) = support::world(cube(), 7).expect("cube world");
    let mut cfg = support::config(cube_band());
    // Wider than the MX-28's Min / Max Position Limit (0…4095, 0…2π rad), so the driver checks.
    cfg.goal_limits_rad.1 = 7.0;
    let mut l = support::grasp_loop(&w, hand, cfg).expect("valid config");
    l.run_until(2_000_000);
    assert!(l.set_goal_rad(7.5).is_err());
    assert!(l.set_goal_rad(f32::NAN).is_err());
    l.run_until(3_000_000);
    assert!(l.log().iter().all(|s| s.fault.is_none()));
    l.set_goal_rad(6.5).expect("within the loop's limits");
    l.run_until(4_000_000);
    every_cycle_logged(&l, 4.0);
    let i =
        common::safe_on_first_fault(l.log(), FaultKind::Command, SafeAction::HoldLastSafeEffort);
    assert!((3_000_000..3_010_000).contains(&l.log()[i].t_us));
    assert!(matches!(
        l.events()[0].fault,
        LoopFault::Command(Error::OutOfRange { what: "goal position (rad)", value, .. })
            if (value - 6.5).abs() < 1e-6
    ));
    let s = w.borrow().state();
    assert!(!s.dropped && !s.damaged, "{s:?}");
}

#[test]
fn tactile_bus_failure_holds_the_grip_and_resumes() {
    // No feedback for 50 ms: the loop cannot control, so it holds the last safe effort.
    let l = with_injection(Injected::TactileBus, 4.0, 4.05, RESUME);
    let i = common::safe_on_first_fault(l.log(), FaultKind::Source, SafeAction::HoldLastSafeEffort);
    assert!(matches!(l.events()[0].fault, LoopFault::Source(_)));
    // Five cycles without a frame, each logged and safe, nothing commanded.
    assert!(
        l.log()[i..i + 5]
            .iter()
            .all(|s| s.frame.is_none() && s.mode == Mode::Safe)
    );
    assert!(l.log()[i..i + 5].iter().all(|s| s.torque_raw.is_none()));
    assert_eq!(l.log()[i + 5].mode, Mode::Grasp);
    assert_eq!(l.mode(), Mode::Grasp);
}

#[test]
fn a_long_run_keeps_a_bounded_log_of_the_newest_cycles_and_counts_the_rest() {
    // A loop left running for hours must not grow its memory with every cycle.
    let (w, hand) = support::world(cube(), 7).expect("cube world");
    let mut cfg = support::config(cube_band());
    cfg.log_capacity = 100;
    let mut l = support::grasp_loop(&w, hand, cfg).expect("valid config");
    l.run_until(8_000_000);
    let kept = l.log().len();
    assert!((50..=100).contains(&kept), "kept {kept}");
    assert!(l.log_dropped() > 600, "dropped {}", l.log_dropped());
    // Nothing lost silently: kept + dropped is every cycle run, and the kept ones are the
    // newest, contiguous, ending with the last cycle.
    let last = l.log().last().expect("kept").cycle;
    assert_eq!(l.log_dropped() + kept as u64, last + 1);
    assert_eq!(l.log()[0].cycle, l.log_dropped());
    assert!(
        l.log()
            .windows(2)
            .all(|p| { (p[1].cycle, p[1].t_us) == (p[0].cycle + 1, p[0].t_us + 10_000) })
    );
    assert_eq!(l.events_dropped(), 0);
    assert!(
        hand_control::grasp_loop::LoopConfig {
            log_capacity: 0,
            ..hand_control::grasp_loop::LoopConfig::new()
        }
        .validate()
        .is_err()
    );
}

#[test]
fn a_world_that_cannot_be_built_is_a_typed_error_not_a_panic() {
    let mut object = cube();
    object.mass_kg = f64::NAN;
    let e = support::world(object.clone(), 7)
        .err()
        .expect("a NaN mass is refused");
    assert!(!e.to_string().is_empty());
    // The summarising entry point reports it the same way.
    let e = support::hold_for("nan cube", object, cube_band(), 7, 1.0)
        .err()
        .expect("refused");
    assert!(matches!(e, support::RigError::Sim(_)), "{e}");
}

/// The soak, short: a minute of simulated grasping with a fault window every 2 s on
/// average, of every kind, each seen as its typed error with the safe state in that cycle,
/// and the loop grasping again after each (`cargo xtask soak` runs the hour per seed).
#[test]
fn a_short_seeded_soak_catches_every_fault_and_recovers() {
    use paper_experiments::soak::{SoakConfig, soak, summary};
    let r = soak(&SoakConfig::short(1, 60.0)).expect("the soak runs");
    eprintln!("{}", summary(&r));
    eprintln!(
        "{}",
        paper_experiments::soak::markdown(std::slice::from_ref(&r))
    );
    assert!(r.violations.is_empty(), "{:#?}", r.violations);
    assert_eq!(r.cycles, 6_000);
    assert_eq!(r.logged + r.log_dropped, r.cycles);
    for k in &r.kinds {
        assert!(k.windows >= 1, "{:?}: no window in a minute", k.kind);
        assert_eq!(k.caught, k.windows, "{k:?}");
        assert_eq!(k.worst_detect_cycles, 0, "{k:?}");
    }
}
