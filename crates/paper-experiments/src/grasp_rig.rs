//! One simulated grasp world behind the three parts a [`GraspLoop`] drives, each at its real
//! interface: the tactile source is hand-sim's barometric [`Fingertip`] read through the real
//! MS5611 driver; the actuator is [`ServoHand`], the Dynamixel driver, talking Protocol 2.0 over
//! a pseudo-terminal to the servo-bus simulator ([`SimBus`]), whose MX-28 drives hand-sim's
//! grasp physics ([`GraspPlant`]); the clock is the fingertip chips' [`SimClock`], to which the
//! servo bus is stepped. Waiting on the clock steps the physics, so a 120 s hold runs in
//! simulated time. Shared by the closed-loop and fault tests, the `grasp_report` example
//! (docs/grasping) and handstack's grasp scene.
//!
//! Faults are injected where they happen on hardware: on the wire (a servo that stops
//! answering, a status packet with a corrupted CRC) and on the fingertip's bus.

use std::cell::RefCell;
use std::rc::Rc;
use std::time::Duration;

use dxl_sim::{Fault, REPLY_LATENCY, SimBus, SimConfig};
use hand_control::control_table::MX_28;
use hand_control::grasp_loop::{
    ConfigError, FaultKind, GraspLoop, LoopClock, LoopConfig, TorqueBand,
};
use hand_control::{PacketCounts, ServoHand};
use hand_sim::SimError;
use hand_sim::fingertip::{Fingertip, FingertipConfig};
use hand_sim::grasp::rig::{ORIGIN_RAD, SERVO_ID};
use hand_sim::grasp::{GraspBody, GraspPlant, GraspState, ObjectParams, RigParams};
use hand_traits::{PressureFrame, TactileSource};
use sim_clock::SimClock;

/// Physics step, s (hand-sim's grasp tests use the same).
pub const DT_S: f64 = 1e-3;
/// When the arm lifts the object, s (hand-sim's `HoldTest` default).
pub const LIFT_AT_S: f64 = 3.0;
/// How long the lifted object is held, s (Table 5: "more than 2 min").
pub const HOLD_S: f64 = 120.0;
/// MS5611 oversampling: OSR 1024 reads three sensors in 4.6 ms, inside a 10 ms cycle.
pub const OSR: u16 = 1024;

/// Smallest pad-force change passed on to the fingertip, N. 5 mN keeps the pad's step history
/// short (and the tests fast) and moves the mean rise by < 0.5 Pa, under the MS5611's 3.6 Pa RMS
/// noise at OSR 1024.
pub const CONTACT_DEAD_BAND_N: f64 = 5e-3;

/// The hardware-error bit [`Injected::HardwareError`] latches: the MX-28's "Electrical Shock
/// Error" (bit 4), which its Shutdown register turns into torque off, as an overload does.
pub const INJECTED_HARDWARE_ERROR: u8 =
    hand_control::control_table::hardware_error::ELECTRICAL_SHOCK;

/// A fault injected during a time window.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Injected {
    /// The servo stops answering (and executing): every exchange times out.
    Silent,
    /// Every status packet arrives with a corrupted CRC.
    Crc,
    /// The fingertip's bus fails (the tactile source's error, not the servo's).
    TactileBus,
    /// The servo executes but its next status packet is lost on the wire, every cycle.
    DropStatus,
    /// The next status packet's header is corrupted (unframeable), every cycle.
    GarbleStatus,
    /// The servo latches a hardware error ([`INJECTED_HARDWARE_ERROR`]) at the window's
    /// start; only a reboot clears it.
    HardwareError,
    /// The fingertip's readings turn NaN (a broken sensor path upstream of the loop).
    NanFrame,
}

impl Injected {
    /// Every kind, in `docs/reliability.md`'s order.
    pub const ALL: [Injected; 7] = [
        Injected::DropStatus,
        Injected::GarbleStatus,
        Injected::Crc,
        Injected::Silent,
        Injected::HardwareError,
        Injected::TactileBus,
        Injected::NanFrame,
    ];
}

/// One injection: `kind` on every cycle in `from_s..until_s`.
#[derive(Debug, Clone, Copy)]
pub struct Injection {
    /// Window start, s.
    pub from_s: f64,
    /// Window end, s.
    pub until_s: f64,
    /// What is injected.
    pub kind: Injected,
}

/// Why a simulated grasp could not be set up, run or summarised.
#[derive(Debug, thiserror::Error)]
pub enum RigError {
    /// The object or the fingertip refused a value, or pressing the pad failed.
    #[error("simulated grasp world: {0}")]
    Sim(#[from] SimError),
    /// The servo-bus simulator could not start or stopped answering.
    #[error("servo-bus simulator: {0}")]
    Bus(#[from] std::io::Error),
    /// The Dynamixel driver could not set up the simulated hand.
    #[error("servo hand: {0}")]
    Hand(#[from] hand_control::Error),
    /// The loop refused its configuration.
    #[error("grasp loop configuration: {0}")]
    Config(#[from] ConfigError),
    /// The loop never sent a torque, so there is nothing to settle (it faulted from the start).
    #[error(
        "the grasp loop sent no torque in {cycles} cycles (first fault: {})",
        fault.map_or_else(|| "none".to_owned(), |f| f.to_string())
    )]
    NoTorque {
        /// Cycles run.
        cycles: usize,
        /// The first fault logged, if any.
        fault: Option<FaultKind>,
    },
}

/// One trace point of the physics (truth the loop never sees).
#[derive(Debug, Clone, Copy)]
pub struct Truth {
    /// Time, s.
    pub t_s: f64,
    /// Pad force, N.
    pub grip_force_n: f64,
    /// Motor current, A.
    pub current_a: f64,
    /// Finger angle, rad.
    pub position_rad: f64,
}

/// The shared world: the bus simulator with its plant, and the fingertip.
pub struct World {
    /// The world's one time: the fingertip chips' clock, which the loop waits on and the
    /// servo bus is stepped to.
    pub clock: SimClock,
    /// The servo-bus simulator (the hand's servo and its plant).
    pub bus: SimBus,
    /// The object between the pads.
    pub plant: GraspPlant,
    /// The fingertip pressed by the object.
    pub tip: Fingertip,
    /// Faults to inject.
    pub injections: Vec<Injection>,
    /// The physics at every loop tick.
    pub trace: Vec<Truth>,
    /// The first failure of the world itself (the bus simulator not answering, the pad
    /// refusing a contact): the world stops there (the clock cannot return an error to the
    /// loop), and [`run_hold_for`] reports it.
    pub world_error: Option<RigError>,
    silent: bool,
    /// Whether the hardware-error window already latched its error.
    latched: bool,
}

impl World {
    fn injected(&self, t_s: f64) -> Option<Injected> {
        self.injections
            .iter()
            .find(|i| (i.from_s..i.until_s).contains(&t_s))
            .map(|i| i.kind)
    }

    /// Lifts the object at `t_s` (default [`LIFT_AT_S`]).
    pub fn lift_at(&self, t_s: f64) {
        self.plant.body().lift_at(t_s);
    }

    /// The physics now: the servo on the bus and the object.
    pub fn state(&self) -> GraspState {
        let body = self.plant.body();
        self.bus
            .with_servo(SERVO_ID, |s| GraspState::of(s, &body))
            .expect("the grasp servo is on the bus")
    }

    /// Sets the wire faults for a cycle starting at `t_s`.
    fn inject_wire(&mut self, t_s: f64) {
        let now = self.injected(t_s);
        let silent = now == Some(Injected::Silent);
        if silent != self.silent {
            if silent {
                self.bus.inject(SERVO_ID, Fault::Mute);
            } else {
                self.bus.clear_faults(SERVO_ID);
            }
            self.silent = silent;
        }
        match now {
            Some(Injected::Crc) => {
                self.bus.inject(SERVO_ID, Fault::CorruptNextCrc);
            }
            Some(Injected::DropStatus) => {
                self.bus.inject(SERVO_ID, Fault::DropNextStatus);
            }
            Some(Injected::GarbleStatus) => {
                self.bus.inject(SERVO_ID, Fault::GarbleNextStatus);
            }
            Some(Injected::HardwareError) if !self.latched => {
                self.bus.with_servo(SERVO_ID, |s| {
                    s.raise_hardware_error(INJECTED_HARDWARE_ERROR)
                });
            }
            _ => {}
        }
        self.latched = now == Some(Injected::HardwareError);
    }

    /// Steps the bus to `t_ns` and presses the pad with every patch change on the way.
    fn advance_to(&mut self, t_ns: u64) -> Result<(), RigError> {
        let now = self.bus.now()?;
        let t = Duration::from_nanos(t_ns);
        if t > now {
            self.bus.advance(t - now)?;
        }
        // Straight from the plant's log into the pad: no copy per cycle.
        let mut body = self.plant.body();
        for (at_ns, patch) in body.take_contacts() {
            self.tip.physics().set_contact(at_ns, patch)?;
        }
        drop(body);
        self.clock.advance_to_ns(t_ns);
        let s = self.state();
        self.trace.push(Truth {
            t_s: s.t_s,
            grip_force_n: s.grip_force_n,
            current_a: s.current_a,
            position_rad: s.position_rad,
        });
        self.inject_wire(t_ns as f64 * 1e-9);
        Ok(())
    }
}

/// The world, shared by the source and the clock.
pub type Shared = Rc<RefCell<World>>;

/// A world with `object` between open fingers and a fingertip seeded with `seed`, and the
/// Dynamixel hand on its bus (position mode, the tuning's gains kept across reboots, torque
/// on).
///
/// Errors: the object or fingertip refusing their configuration, the bus or the hand failing
/// to start.
pub fn world(object: ObjectParams, seed: u64) -> Result<(Shared, ServoHand), RigError> {
    let rig = RigParams::default();
    object.validate()?;
    rig.validate()?;
    let mut body = GraspBody::new(object, rig, ORIGIN_RAD);
    body.lift_at(LIFT_AT_S);
    body.log_contacts(CONTACT_DEAD_BAND_N);
    let plant = GraspPlant::new(body);
    let (bus, port) = SimBus::spawn(SimConfig {
        params: rig.servo.params(),
        step: Duration::from_secs_f64(DT_S),
        initial_position_rad: ORIGIN_RAD,
        ..SimConfig::with_ids(&[SERVO_ID])
    })?;
    bus.set_plant(SERVO_ID, plant.clone());
    let mut hand = ServoHand::with_reply_latency(port, &[SERVO_ID], REPLY_LATENCY)?;
    hand.set_position_mode()?;
    let settings = rig
        .servo
        .registers()
        .map(|(name, value)| MX_28.register(name).map(|r| (r.address, value)));
    let settings: Option<Vec<_>> = settings.into_iter().collect();
    let settings = settings.ok_or(SimError::config("servo", "not an MX-28(2.0) register"))?;
    hand.keep_ram_settings(&settings)?;
    hand.set_torque(true)?;
    let tip = Fingertip::new(
        &FingertipConfig {
            osr: OSR,
            ..FingertipConfig::default()
        },
        seed,
    )?;
    let world = World {
        clock: tip.clock(),
        bus,
        plant,
        tip,
        injections: Vec::new(),
        trace: Vec::new(),
        world_error: None,
        silent: false,
        latched: false,
    };
    Ok((Rc::new(RefCell::new(world)), hand))
}

/// The fingertip as the loop's tactile source.
pub struct Source(pub Shared);

impl TactileSource for Source {
    type Frame = PressureFrame<3>;
    type Error = SimError;
    fn read_frame(&mut self) -> Result<PressureFrame<3>, SimError> {
        let mut w = self.0.borrow_mut();
        let t_s = w.clock.now_ns() as f64 * 1e-9;
        match w.injected(t_s) {
            Some(Injected::TactileBus) => Err(SimError::Driver {
                model: "fingertip",
                detail: "injected SPI failure".into(),
            }),
            Some(Injected::NanFrame) => w.tip.read_frame().map(|mut f| {
                f.pressure_pa[0] = f32::NAN;
                f
            }),
            _ => w.tip.read_frame(),
        }
    }
}

/// The world's time as the loop's clock: waiting steps the bus and its physics.
pub struct Clock(pub Shared);

impl LoopClock for Clock {
    fn now_us(&mut self) -> u64 {
        // One time for the world: the fingertip's clock, which its chips advance as their bus
        // carries bits. An exchange on the servo bus moves the bus's time by its wire time, so
        // the clock catches up with it before anyone reads it. A bus that cannot tell its time
        // stops the world as `wait_until_us` does.
        let mut w = self.0.borrow_mut();
        match w.bus.now() {
            Ok(t) => w.clock.advance_to_ns(t.as_nanos() as u64),
            Err(e) => {
                w.world_error.get_or_insert(e.into());
            }
        }
        w.clock.now_us()
    }

    fn wait_until_us(&mut self, t_us: u64) {
        // The clock cannot hand an error to the loop: keep the first one and stop the world
        // there for `run_hold_for` to report (the loop's own ticks still advance, so a run ends).
        let mut w = self.0.borrow_mut();
        if w.world_error.is_none() {
            if let Err(e) = w.advance_to(t_us * 1000) {
                w.world_error = Some(e);
            }
        }
    }
}

/// The loop over the simulated world with the paper's fuzzy controller.
pub type SimLoop = GraspLoop<Source, fuzzy_mamdani::GraspController, ServoHand, Clock, 3>;

/// The loop configuration the closed-loop tests use for `band`: goal 15 mm past first contact
/// (hand-sim's `close()`), as the Table 5 calibration assumes, from the servo's start angle.
pub fn config(band: TorqueBand) -> LoopConfig {
    let rig = RigParams::default();
    let goal = ORIGIN_RAD + rig.goal_for_squeeze_rad(rig.goal_squeeze_m);
    LoopConfig {
        band,
        goal_rad: goal as f32,
        goal_limits_rad: (ORIGIN_RAD as f32, (ORIGIN_RAD + 0.5) as f32),
        ..LoopConfig::new()
    }
}

/// A loop over `world` and `hand` with `config` (errors: the loop refusing `config`).
pub fn grasp_loop(
    world: &Shared,
    hand: ServoHand,
    config: LoopConfig,
) -> Result<SimLoop, ConfigError> {
    GraspLoop::new(
        Source(world.clone()),
        fuzzy_mamdani::grasp_controller()
            .with_torque_band(config.band.min_raw(), config.band.max_raw()),
        hand,
        Clock(world.clone()),
        config,
    )
}

/// Runs the full Table 5 protocol: close, lift at 3 s, hold 120 s.
pub fn run_hold(world: &Shared, hand: ServoHand, config: LoopConfig) -> Result<SimLoop, RigError> {
    run_hold_for(world, hand, config, HOLD_S)
}

/// Close, lift at 3 s, hold `hold_s` seconds. Errors: the configuration, or the world failing
/// on the way (it stopped there).
pub fn run_hold_for(
    world: &Shared,
    hand: ServoHand,
    config: LoopConfig,
    hold_s: f64,
) -> Result<SimLoop, RigError> {
    let mut l = grasp_loop(world, hand, config)?;
    // The loop's ticks advance even over a stopped world, so this ends either way.
    l.run_until(((LIFT_AT_S + hold_s) * 1e6) as u64);
    match world.borrow_mut().world_error.take() {
        Some(e) => Err(e),
        None => Ok(l),
    }
}

pub use hand_control::grasp_loop::{SETTLE_TOL_RAW, SETTLE_WINDOW_US};

/// What one closed-loop hold gave.
#[derive(Debug, Clone)]
pub struct Outcome {
    /// The object.
    pub name: String,
    /// The torque band, 0…1023.
    pub band: (u16, u16),
    /// Mean torque sent over the last [`SETTLE_WINDOW_US`].
    pub settled_raw: f32,
    /// Least and greatest torque sent in that window.
    pub window_raw: (u16, u16),
    /// From the first command until every torque stays within [`SETTLE_TOL_RAW`], s.
    pub settling_time_s: f64,
    /// Highest pad force, N (physics truth).
    pub peak_force_n: f64,
    /// Pad force at the end, N.
    pub final_force_n: f64,
    /// The loop's last mean pressure rise, Pa.
    pub final_pressure_pa: f32,
    /// How far the object slid, m.
    pub slip_m: f64,
    /// Slid beyond hand-sim's tolerance.
    pub slipped: bool,
    /// Crushed.
    pub damaged: bool,
    /// Dropped.
    pub dropped: bool,
    /// Fault events the loop logged.
    pub faults: usize,
    /// Loop cycles run.
    pub cycles: usize,
    /// Ticks the loop missed.
    pub missed_ticks: u64,
    /// Protocol 2.0 packets the driver sent and received over the hold (set-up included).
    pub packets: PacketCounts,
    /// The loop's mode at the end.
    pub mode: hand_control::grasp_loop::Mode,
}

/// Runs the Table 5 protocol on `object` inside `band` and summarises it.
pub fn hold(
    name: &str,
    object: ObjectParams,
    band: TorqueBand,
    seed: u64,
) -> Result<(Outcome, SimLoop, Shared), RigError> {
    hold_for(name, object, band, seed, HOLD_S)
}

/// [`hold`] with a hold of `hold_s` seconds after the lift.
pub fn hold_for(
    name: &str,
    object: ObjectParams,
    band: TorqueBand,
    seed: u64,
    hold_s: f64,
) -> Result<(Outcome, SimLoop, Shared), RigError> {
    let (w, hand) = world(object, seed)?;
    let mut l = run_hold_for(&w, hand, config(band), hold_s)?;
    let st = hand_control::grasp_loop::settling(l.log(), SETTLE_WINDOW_US, SETTLE_TOL_RAW)
        .ok_or_else(|| RigError::NoTorque {
            cycles: l.log().len(),
            fault: l.log().iter().find_map(|s| s.fault),
        })?;
    let s = w.borrow().state();
    let peak_force_n = w.borrow().plant.body().peak_force_n();
    let last = l.log().last().and_then(|s| s.estimate);
    let o = Outcome {
        name: name.to_owned(),
        band: (band.min_raw(), band.max_raw()),
        settled_raw: st.settled_raw,
        window_raw: st.window_raw,
        settling_time_s: st.settling_time_us as f64 * 1e-6,
        peak_force_n,
        final_force_n: s.grip_force_n,
        final_pressure_pa: last.map_or(f32::NAN, |e| e.pressure_pa),
        slip_m: s.slip_m,
        slipped: s.slip_m > hand_sim::grasp::rig::SLIP_TOLERANCE_M,
        damaged: s.damaged,
        dropped: s.dropped,
        faults: l.events().len(),
        cycles: l.log().len(),
        missed_ticks: l.missed_ticks(),
        packets: l.actuator_mut().packet_counts(),
        mode: l.mode(),
    };
    Ok((o, l, w))
}
