//! One simulated grasp world: hand-sim's [`GraspRig`] squeezing an object and
//! pressing hand-sim's barometric [`Fingertip`], read through the real MS5611 driver, behind the
//! three parts a [`GraspLoop`] drives: a tactile source, an actuator and a clock. Waiting on the
//! clock steps the physics, so a 120 s hold runs in simulated time. Shared by the closed-loop
//! and fault tests, the `grasp_report` example (docs/grasping) and handstack's grasp scene.
//!
//! The actuator here is in-process (it calls the rig directly); its transport faults (lost
//! status packet, CRC mismatch, silence, range error) are injected by time window.

use hand_control::grasp_loop::{
    ConfigError, FaultKind, GraspLoop, LoopClock, LoopConfig, RebootableActuator, TorqueBand,
};
use hand_sim::SimError;
use hand_sim::fingertip::{ContactPatch, Fingertip, FingertipConfig};
use hand_sim::grasp::{GraspRig, GraspState, ObjectParams, RigParams};
use hand_traits::{
    GripperActuator, GripperCommand, GripperState, PressureFrame, SafeAction, TactileSource,
};
use std::cell::RefCell;
use std::rc::Rc;

/// Physics step, s (hand-sim's grasp tests use the same).
pub const DT_S: f64 = 1e-3;
/// When the arm lifts the object, s (hand-sim's `HoldTest` default).
pub const LIFT_AT_S: f64 = 3.0;
/// How long the lifted object is held, s (Table 5: "more than 2 min").
pub const HOLD_S: f64 = 120.0;
/// MS5611 oversampling: OSR 1024 reads three sensors in 4.6 ms, inside a 10 ms cycle.
pub const OSR: u16 = 1024;

/// Smallest pad-force change passed on to the fingertip, N.
pub const CONTACT_DEAD_BAND_N: f64 = 5e-3;

/// A transport fault the simulated servo shows during a time window.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Injected {
    /// The status packet never arrives (read times out).
    LostStatus,
    /// The status packet arrives with a wrong CRC.
    Crc,
    /// The fingertip's SPI bus fails (the tactile source's error, not the servo's).
    TactileBus,
}

/// One injection: `kind` on every call in `from_s..until_s`.
#[derive(Debug, Clone, Copy)]
pub struct Injection {
    /// Window start, s.
    pub from_s: f64,
    /// Window end, s.
    pub until_s: f64,
    /// What is injected.
    pub kind: Injected,
}

/// The simulated servo's errors.
#[derive(Debug)]
pub enum HandError {
    /// No status packet.
    Timeout,
    /// Status packet CRC mismatch.
    Crc,
    /// The servo refused a value (Dynamixel "Data Range Error").
    Range {
        /// The refused goal, rad.
        goal_rad: f32,
    },
    /// The rig refused (e.g. torque on while the overload bit is latched).
    Sim(SimError),
}

/// Why a simulated grasp could not be set up, run or summarised.
#[derive(Debug, thiserror::Error)]
pub enum RigError {
    /// The rig, its object or the fingertip refused a value, or a physics step failed.
    #[error("simulated grasp world: {0}")]
    Sim(#[from] SimError),
    /// The loop refused its configuration.
    #[error("grasp loop configuration: {0}")]
    Config(#[from] ConfigError),
    /// The loop never sent a torque, so there is nothing to settle (it faulted from the start).
    #[error("the grasp loop sent no torque in {cycles} cycles (first fault: {fault:?})")]
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

/// The shared world.
pub struct World {
    /// The two-finger rig and its object.
    pub rig: GraspRig,
    /// The fingertip pressed by the rig.
    pub tip: Fingertip,
    t_ns: u64,
    patch: ContactPatch,
    /// Transport faults to inject.
    pub injections: Vec<Injection>,
    /// The servo's goal limits, rad (Min / Max Position Limit).
    pub servo_goal_limits_rad: (f32, f32),
    /// Highest pad force so far, N.
    pub peak_force_n: f64,
    /// Whether the object ever slipped.
    pub ever_slipping: bool,
    /// The physics at every loop tick.
    pub trace: Vec<Truth>,
    /// When the arm lifts the object, s ([`LIFT_AT_S`] unless a test needs it earlier).
    pub lift_at_s: f64,
    /// The first physics step that failed: the world stops there (the clock cannot return
    /// an error to the loop), and [`hold_for`] reports it.
    pub physics_error: Option<SimError>,
}

impl World {
    fn now_s(&self) -> f64 {
        self.t_ns as f64 * 1e-9
    }

    fn injected(&self) -> Option<Injected> {
        let t = self.now_s();
        self.injections
            .iter()
            .find(|i| (i.from_s..i.until_s).contains(&t))
            .map(|i| i.kind)
    }

    /// Steps the rig to `t_ns` and presses the pad with its contact patch.
    fn advance_to(&mut self, t_ns: u64) -> Result<(), SimError> {
        let dt_ns = (DT_S * 1e9) as u64;
        while self.t_ns + dt_ns <= t_ns {
            self.rig.set_lifted(self.now_s() >= self.lift_at_s);
            let s = self.rig.step(DT_S)?;
            self.t_ns += dt_ns;
            self.peak_force_n = self.peak_force_n.max(s.grip_force_n);
            self.ever_slipping |= s.slipping;
            // A 5 mN dead band keeps the pad's step history short (and the tests fast); 5 mN
            // moves the mean rise by < 0.5 Pa, under the MS5611's 3.6 Pa RMS noise at OSR 1024.
            if s.patch.cells != self.patch.cells
                || (s.patch.force_n - self.patch.force_n).abs() > CONTACT_DEAD_BAND_N
            {
                self.tip.physics().set_contact(self.t_ns, s.patch)?;
                self.patch = s.patch;
            }
        }
        self.tip.idle_until_ns(t_ns);
        let s = self.rig.state();
        self.trace.push(Truth {
            t_s: self.now_s(),
            grip_force_n: s.grip_force_n,
            current_a: s.current_a,
            position_rad: s.position_rad,
        });
        Ok(())
    }

    /// The rig's state now.
    pub fn state(&self) -> GraspState {
        self.rig.state()
    }
}

/// The world, shared by the source, the actuator and the clock.
pub type Shared = Rc<RefCell<World>>;

/// A world with `object` between open fingers and a fingertip seeded with `seed`.
///
/// Errors: the rig or the fingertip refusing the object or its configuration.
pub fn world(object: ObjectParams, seed: u64) -> Result<Shared, SimError> {
    let rig = GraspRig::new(object, RigParams::default())?;
    let config = FingertipConfig {
        osr: OSR,
        ..FingertipConfig::default()
    };
    let tip = Fingertip::new(&config, seed)?;
    Ok(Rc::new(RefCell::new(World {
        rig,
        tip,
        t_ns: 0,
        patch: ContactPatch::NONE,
        injections: Vec::new(),
        servo_goal_limits_rad: (0.0, 1.0),
        peak_force_n: 0.0,
        ever_slipping: false,
        trace: Vec::new(),
        lift_at_s: LIFT_AT_S,
        physics_error: None,
    })))
}

/// The fingertip as the loop's tactile source.
pub struct Source(pub Shared);

impl TactileSource for Source {
    type Frame = PressureFrame<3>;
    type Error = SimError;
    fn read_frame(&mut self) -> Result<PressureFrame<3>, SimError> {
        if self.0.borrow().injected() == Some(Injected::TactileBus) {
            return Err(SimError::Driver {
                model: "fingertip",
                detail: "injected SPI failure".into(),
            });
        }
        self.0.borrow_mut().tip.read_frame()
    }
}

/// The rig's servo as the loop's actuator.
pub struct Hand(pub Shared);

impl Hand {
    fn transport(&self) -> Result<(), HandError> {
        match self.0.borrow().injected() {
            Some(Injected::LostStatus) => Err(HandError::Timeout),
            Some(Injected::Crc) => Err(HandError::Crc),
            Some(Injected::TactileBus) | None => Ok(()),
        }
    }
}

impl GripperActuator for Hand {
    type Error = HandError;

    fn command(&mut self, cmd: &GripperCommand) -> Result<(), HandError> {
        self.transport()?;
        let mut w = self.0.borrow_mut();
        let (lo, hi) = w.servo_goal_limits_rad;
        if !(lo..=hi).contains(&cmd.position_rad) {
            return Err(HandError::Range {
                goal_rad: cmd.position_rad,
            });
        }
        let rig = &mut w.rig;
        rig.set_torque_limit(cmd.effort.to_torque_limit_raw())
            .map_err(HandError::Sim)?;
        rig.set_goal_rad(f64::from(cmd.position_rad))
            .map_err(HandError::Sim)
    }

    fn state(&mut self) -> Result<GripperState, HandError> {
        self.transport()?;
        let s = self.0.borrow().rig.state();
        Ok(GripperState {
            position_rad: s.position_rad as f32,
            velocity_rad_per_s: s.velocity_rad_s as f32,
            load_fraction: s.load_fraction as f32,
            faults: s.faults,
        })
    }

    fn safe_stop(&mut self, action: SafeAction) -> Result<(), HandError> {
        self.transport()?;
        match action {
            // The servo keeps its goal and the limit last written: it holds.
            SafeAction::HoldLastSafeEffort => Ok(()),
            SafeAction::TorqueOff => self
                .0
                .borrow_mut()
                .rig
                .set_torque_enabled(false)
                .map_err(HandError::Sim),
        }
    }
}

impl RebootableActuator for Hand {
    fn reboot(&mut self) -> Result<(), HandError> {
        self.transport()?;
        // REBOOT clears the latched error with torque off; enable it again, as a driver's
        // recovery does, so the next command moves the fingers.
        let rig = &mut self.0.borrow_mut().rig;
        rig.reboot();
        rig.set_torque_enabled(true).map_err(HandError::Sim)
    }

    fn enable_torque(&mut self) -> Result<(), HandError> {
        self.transport()?;
        self.0
            .borrow_mut()
            .rig
            .set_torque_enabled(true)
            .map_err(HandError::Sim)
    }
}

/// The world's time as the loop's clock: waiting steps the physics.
pub struct Clock(pub Shared);

impl LoopClock for Clock {
    fn now_us(&mut self) -> u64 {
        // The bus clock runs ahead of the rig by the frame just read.
        let w = self.0.borrow();
        w.t_ns.max(w.tip.now_ns()) / 1000
    }

    fn wait_until_us(&mut self, t_us: u64) {
        // The clock cannot hand an error to the loop: keep the first one and stop the world
        // there for `hold_for` to report (time stands still; the loop's own ticks still
        // advance, so a run ends).
        let mut w = self.0.borrow_mut();
        if w.physics_error.is_none() {
            if let Err(e) = w.advance_to(t_us * 1000) {
                w.physics_error = Some(e);
            }
        }
    }
}

/// The loop over the simulated world with the paper's fuzzy controller.
pub type SimLoop = GraspLoop<Source, fuzzy_mamdani::GraspController, Hand, Clock, 3>;

/// The loop configuration the closed-loop tests use for `band`.
pub fn config(band: TorqueBand) -> LoopConfig {
    let rig = RigParams::default();
    // Goal 15 mm past first contact (hand-sim's `close()`), as the Table 5 calibration assumes.
    let goal = (rig.approach_m + rig.goal_squeeze_m) / rig.linkage.lever_m;
    LoopConfig {
        band,
        goal_rad: goal as f32,
        goal_limits_rad: (0.0, 0.5),
        ..LoopConfig::new()
    }
}

/// A loop over `world` with `config` (errors: the loop refusing `config`).
pub fn grasp_loop(world: &Shared, config: LoopConfig) -> Result<SimLoop, ConfigError> {
    GraspLoop::new(
        Source(world.clone()),
        fuzzy_mamdani::grasp_controller()
            .with_torque_band(config.band.min_raw(), config.band.max_raw()),
        Hand(world.clone()),
        Clock(world.clone()),
        config,
    )
}

/// Runs the full Table 5 protocol: close, lift at 3 s, hold 120 s.
pub fn run_hold(world: &Shared, config: LoopConfig) -> Result<SimLoop, RigError> {
    run_hold_for(world, config, HOLD_S)
}

/// Close, lift at 3 s, hold `hold_s` seconds. Errors: the configuration, or a physics step
/// that failed on the way (the world stopped there).
pub fn run_hold_for(world: &Shared, config: LoopConfig, hold_s: f64) -> Result<SimLoop, RigError> {
    let mut l = grasp_loop(world, config)?;
    // The loop's ticks advance even over a stopped world, so this ends either way.
    l.run_until(((LIFT_AT_S + hold_s) * 1e6) as u64);
    match world.borrow_mut().physics_error.take() {
        Some(e) => Err(e.into()),
        None => Ok(l),
    }
}

/// Tolerance of the settling time, counts: 2 % of the 0…1023 scale (the MS5611 noise through
/// the filtered rate moves the torque by several counts from cycle to cycle).
pub const SETTLE_TOL_RAW: f32 = 20.0;
/// Window at the end of the hold the settled torque is averaged over, µs.
pub const SETTLE_WINDOW_US: u64 = 10_000_000;

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
    let w = world(object, seed)?;
    let l = run_hold_for(&w, config(band), hold_s)?;
    let st = hand_control::grasp_loop::settling(l.log(), SETTLE_WINDOW_US, SETTLE_TOL_RAW)
        .ok_or_else(|| RigError::NoTorque {
            cycles: l.log().len(),
            fault: l.log().iter().find_map(|s| s.fault),
        })?;
    let s = w.borrow().state();
    let last = l.log().last().and_then(|s| s.estimate);
    let o = Outcome {
        name: name.to_owned(),
        band: (band.min_raw(), band.max_raw()),
        settled_raw: st.settled_raw,
        window_raw: st.window_raw,
        settling_time_s: st.settling_time_us as f64 * 1e-6,
        peak_force_n: w.borrow().peak_force_n,
        final_force_n: s.grip_force_n,
        final_pressure_pa: last.map_or(f32::NAN, |e| e.pressure_pa),
        slip_m: s.slip_m,
        slipped: s.slip_m > hand_sim::grasp::rig::SLIP_TOLERANCE_M,
        damaged: s.damaged,
        dropped: s.dropped,
        faults: l.events().len(),
        cycles: l.log().len(),
        missed_ticks: l.missed_ticks(),
        mode: l.mode(),
    };
    Ok((o, l, w))
}
