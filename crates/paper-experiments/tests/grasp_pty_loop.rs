//! The grasp loop through the real interface: `ServoHand` (dynamixel2 over serial2) talking
//! Protocol 2.0 over a pseudo-terminal to the simulated MX-28 bus, whose plant hook carries a
//! hand-sim object (its squeeze law, `hand_sim::grasp::contact`), and whose pad force presses
//! hand-sim's fingertip (three MS5611 models through the real driver).
//!
//! One closed-loop grasp, then the fault cases on the wire: a dropped status packet, a
//! corrupted CRC, a servo that stops answering, the servo's own overload, an out-of-range goal.

mod common;

use hand_control::grasp_loop::{
    FaultKind, GraspLoop, LoopClock, LoopConfig, LoopFault, Mode, Recovery, TorqueBand,
};
use hand_control::sim::{Fault, SimBus, SimConfig};
use hand_control::{Error, ServoHand};
use hand_sim::SimError;
use hand_sim::fingertip::{Fingertip, FingertipConfig};
use hand_sim::grasp::contact;
use hand_sim::grasp::object::G;
use hand_sim::grasp::rig::CRUSH_TIME_S;
use hand_sim::grasp::{ObjectKind, ObjectParams, RigParams};
use hand_traits::{Faults, PressureFrame, SafeAction, TactileSource};
use std::cell::RefCell;
use std::f64::consts::PI;
use std::rc::Rc;
use std::sync::{Arc, Mutex};
use std::time::Duration;

/// Both fingers' servos on one bus.
const IDS: [u8; 2] = [1, 2];

/// The bus, the fingertip and the pad force the plant last computed.
struct World {
    bus: SimBus,
    tip: Fingertip,
    object: ObjectParams,
    force_n: Arc<Mutex<f64>>,
    /// The plant's pad force at each tick, (µs, N).
    trace: Vec<(u64, f64)>,
}

type Shared = Rc<RefCell<World>>;

struct Source(Shared);

impl TactileSource for Source {
    type Frame = PressureFrame<3>;
    type Error = SimError;
    fn read_frame(&mut self) -> Result<PressureFrame<3>, SimError> {
        self.0.borrow_mut().tip.read_frame()
    }
}

/// The bus's simulated time: waiting advances the servos (and their plant), then presses the
/// pad with the plant's force (held for the cycle: the pad sees it at 100 Hz).
struct Clock(Shared);

impl LoopClock for Clock {
    fn now_us(&mut self) -> u64 {
        let w = self.0.borrow();
        (w.bus.now().as_nanos() as u64).max(w.tip.now_ns()) / 1000
    }

    fn wait_until_us(&mut self, t_us: u64) {
        let now = self.now_us();
        let mut w = self.0.borrow_mut();
        if t_us > now {
            w.bus
                .advance(Duration::from_micros(t_us - now))
                .expect("simulator answers");
        }
        let force = *w.force_n.lock().expect("plant lock");
        w.trace.push((t_us, force));
        let patch = contact::patch(&w.object, force);
        w.tip.set_contact(patch).expect("contact in time order");
        w.tip.idle_until_ns(t_us * 1000);
    }
}

type PtyLoop = GraspLoop<Source, fuzzy_mamdani::GraspController, ServoHand, Clock, 3>;

/// A bus whose servos squeeze `object` (each servo's output is one finger, starting at π rad,
/// the pads `approach_m` from the surface), a hand on it, and a loop inside `band`.
fn setup(
    object: ObjectParams,
    band: TorqueBand,
    tune: impl FnOnce(&mut LoopConfig),
) -> (PtyLoop, Shared) {
    let rig = RigParams::default();
    let (bus, port) = SimBus::spawn(SimConfig::with_ids(&IDS)).expect("pty");
    let force_n = Arc::new(Mutex::new(0.0));
    for id in IDS {
        let (obj, force) = (object.clone(), force_n.clone());
        bus.set_plant(id, move |pos: f64, vel: f64, _t: Duration| {
            let lin = contact::load(pos - PI, &obj, &rig);
            if id == IDS[0] {
                *force.lock().expect("plant lock") = contact::pad_force_n(&lin, vel, &rig);
            }
            lin.torque_nm + lin.damping_nm_s_per_rad * vel
        });
    }
    let mut hand = ServoHand::new(port, &IDS).expect("identify");
    hand.set_position_mode().expect("mode");
    hand.set_torque(true).expect("torque on");
    let tip = Fingertip::new(
        &FingertipConfig {
            osr: 1024,
            ..FingertipConfig::default()
        },
        7,
    )
    .expect("fingertip");
    let w = Rc::new(RefCell::new(World {
        bus,
        tip,
        object,
        force_n,
        trace: Vec::new(),
    }));
    let goal = PI + (rig.approach_m + rig.goal_squeeze_m) / rig.linkage.lever_m;
    let mut config = LoopConfig {
        band,
        goal_rad: goal as f32,
        goal_limits_rad: (PI as f32, (PI + 0.5) as f32),
        ..LoopConfig::new()
    };
    tune(&mut config);
    let policy = fuzzy_mamdani::grasp_controller().with_torque_band(band.min_raw(), band.max_raw());
    let l = GraspLoop::new(Source(w.clone()), policy, hand, Clock(w.clone()), config)
        .expect("valid config");
    (l, w)
}

fn cube() -> ObjectParams {
    ObjectParams::table5(ObjectKind::Cube, &RigParams::default()).expect("cube")
}

fn cube_band() -> TorqueBand {
    TorqueBand::new(80, 400).expect("Table 5 cube")
}

#[test]
fn closed_loop_grasp_through_the_driver_holds_the_cube() {
    let (mut l, w) = setup(cube(), cube_band(), |_| {});
    l.run_until(5_000_000);
    common::ticks_in_order(l.log());
    assert!(l.events().is_empty(), "{:?}", l.events());
    assert_eq!(l.mode(), Mode::Grasp);
    let st = hand_control::grasp_loop::settling(l.log(), 1_000_000, 20.0).expect("commands sent");
    assert!(st.window_raw.0 >= 80 && st.window_raw.1 <= 400, "{st:?}");
    assert!(st.window_raw.1 - st.window_raw.0 <= 40, "{st:?}");
    // The grip the driver's servo settles on holds the cube by hand-sim's slide rule
    // (2 µ F ≥ m g) and stays under its crush force.
    let w = w.borrow();
    let f = *w.force_n.lock().expect("plant lock");
    let peak = w.trace.iter().map(|p| p.1).fold(0.0, f64::max);
    eprintln!("settling {st:?}, pad force {f:.2} N, peak {peak:.2} N"); // shown on failure

    let o = &w.object;
    assert!(
        2.0 * o.material.friction * f >= o.mass_kg * G,
        "grip {f} N too weak"
    );
    // hand-sim crushes an object held at or above its crush force for CRUSH_TIME_S (0.5 s);
    // this servo closes faster than hand-sim's and the impact peaks above it for a few ms.
    let mut run_us = 0;
    let mut longest_us = 0;
    for pair in w.trace.windows(2) {
        run_us = if pair[0].1 >= o.damage_force_n {
            run_us + pair[1].0 - pair[0].0
        } else {
            0
        };
        longest_us = longest_us.max(run_us);
    }
    assert!(
        (longest_us as f64) < CRUSH_TIME_S * 1e6,
        "{longest_us} µs above the crush force"
    );
}

#[test]
fn dropped_status_packet_on_the_wire_is_a_timeout_and_safe() {
    let auto = Recovery::Automatic {
        cooldown_us: 0,
        max_reboots: 0,
    };
    let (mut l, w) = setup(cube(), cube_band(), |c| c.recovery = auto);
    l.run_until(2_000_000);
    w.borrow().bus.inject(1, Fault::DropNextStatus);
    l.run_until(2_500_000);
    common::ticks_in_order(l.log());
    let i = common::safe_on_first_fault(l.log(), FaultKind::State, SafeAction::HoldLastSafeEffort);
    // Servo 1's status missing from the sync read: that servo's timeout.
    assert!(matches!(
        l.events()[0].fault,
        LoopFault::State(Error::Timeout { id: Some(1) })
    ));
    assert_eq!(l.log()[i + 1].mode, Mode::Grasp);
    assert_eq!(l.mode(), Mode::Grasp);
}

#[test]
fn corrupted_crc_on_the_wire_is_typed_and_safe() {
    let (mut l, w) = setup(cube(), cube_band(), |_| {});
    l.run_until(2_000_000);
    w.borrow().bus.inject(2, Fault::CorruptNextCrc);
    l.run_until(2_500_000);
    common::ticks_in_order(l.log());
    let i = common::safe_on_first_fault(l.log(), FaultKind::State, SafeAction::HoldLastSafeEffort);
    assert!(matches!(
        l.events()[0].fault,
        LoopFault::State(Error::Crc { .. })
    ));
    // Manual recovery: safe from then on, nothing more commanded.
    assert!(
        l.log()[i + 1..]
            .iter()
            .all(|s| s.mode == Mode::Safe && s.torque_raw.is_none())
    );
}

#[test]
fn mute_servo_keeps_the_loop_safe_until_it_answers() {
    let auto = Recovery::Automatic {
        cooldown_us: 0,
        max_reboots: 0,
    };
    let (mut l, w) = setup(cube(), cube_band(), |c| {
        c.recovery = auto;
        c.safe_action = SafeAction::TorqueOff;
    });
    l.run_until(2_000_000);
    w.borrow().bus.inject(1, Fault::Mute);
    l.run_until(2_100_000);
    // Torque off is one broadcast write: it reached servo 2 while servo 1 was mute.
    assert_eq!(
        w.borrow().bus.with_servo(2, |s| s.torque_enabled()),
        Some(false)
    );
    w.borrow().bus.clear_faults(1);
    l.run_until(3_000_000);
    common::ticks_in_order(l.log());
    let i = common::safe_on_first_fault(l.log(), FaultKind::State, SafeAction::TorqueOff);
    assert!(matches!(
        l.events()[0].fault,
        LoopFault::State(Error::Timeout { id: Some(1) })
    ));
    // Silent: no state, safe, every cycle logged; nothing commanded after the fault's cycle
    // (whose broadcast sync write went out before the read failed).
    assert!(
        l.log()[i..i + 5]
            .iter()
            .all(|s| s.mode == Mode::Safe && s.state.is_none())
    );
    assert!(l.log()[i + 1..i + 5].iter().all(|s| s.torque_raw.is_none()));
    // Answering again: torque back on, grasping, the cube pressed again.
    assert_eq!(l.mode(), Mode::Grasp);
    assert_eq!(
        w.borrow().bus.with_servo(1, |s| s.torque_enabled()),
        Some(true)
    );
    let last = l.log().last().and_then(|s| s.estimate).expect("estimate");
    assert!(last.in_contact, "{last:?}");
}

#[test]
fn servo_overload_bit_goes_torque_off_then_reboots_over_the_wire() {
    let auto = Recovery::Automatic {
        cooldown_us: 300_000,
        max_reboots: 1,
    };
    let (mut l, w) = setup(cube(), cube_band(), |c| {
        c.recovery = auto;
        c.safe_action = SafeAction::TorqueOff;
    });
    l.run_until(2_000_000);
    // The firmware's overload (Hardware Error Status bit 5; Shutdown's default includes it).
    w.borrow()
        .bus
        .with_servo(1, |s| s.raise_hardware_error(0x20))
        .expect("servo 1");
    l.run_until(4_000_000);
    common::ticks_in_order(l.log());
    let i = common::safe_on_first_fault(
        l.log(),
        FaultKind::Hardware(Faults::OVERLOAD),
        SafeAction::TorqueOff,
    );
    let reboot = l.log().iter().position(|s| s.rebooted).expect("rebooted");
    assert!(l.log()[reboot].t_us - l.log()[i].t_us >= 300_000);
    assert!(
        l.log()[i + 1..reboot]
            .iter()
            .all(|s| s.torque_raw.is_none())
    );
    // REBOOT over the wire cleared the latched bit; grasping resumed.
    assert_eq!((l.mode(), l.reboots()), (Mode::Grasp, 1));
    assert_eq!(
        w.borrow().bus.with_servo(1, |s| s.hardware_error()),
        Some(0)
    );
    assert!(
        l.log()
            .last()
            .and_then(|s| s.estimate)
            .expect("estimate")
            .in_contact
    );
}

#[test]
fn out_of_range_goal_is_refused_by_the_loop_and_the_driver() {
    let (mut l, _w) = setup(cube(), cube_band(), |c| c.goal_limits_rad = (0.0, 7.0));
    l.run_until(1_000_000);
    assert!(l.set_goal_rad(7.5).is_err());
    // Inside the loop's (too wide) limits, outside the MX-28's 0…4095 ticks: the driver refuses
    // before sending.
    l.set_goal_rad(6.6).expect("within the loop's limits");
    l.run_until(1_500_000);
    common::ticks_in_order(l.log());
    let _ =
        common::safe_on_first_fault(l.log(), FaultKind::Command, SafeAction::HoldLastSafeEffort);
    assert!(matches!(
        l.events()[0].fault,
        LoopFault::Command(Error::OutOfRange { .. })
    ));
}
