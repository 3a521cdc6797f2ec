//! One grasp: two opposing fingers, each on an MX-28, squeezing one object, then lifting it.
//! The plain API an open-loop sweep drives in process: set the torque limit and goal, step,
//! read. The motor is [`dxl_sim::SimServo`] (the bus simulator's), the object its
//! [`GraspPlant`]; by symmetry one servo stands for both fingers.

use std::time::Duration;

use dxl_sim::SimServo;
use hand_control::control_table::MX_28;
use hand_traits::Faults;
use serde::{Deserialize, Serialize};

use super::linkage::Linkage;
use super::object::ObjectParams;
use super::plant::{GraspBody, GraspPlant};
use super::servo::{ServoTuning, TORQUE_LIMIT_MAX, positive};
use crate::SimError;
use crate::fingertip::ContactPatch;

/// The servo angle the grasp starts at, rad: Present Position 2048, mid-range, so the closing
/// goal stays inside Position Control Mode's 0…4095.
pub const ORIGIN_RAD: f64 = core::f64::consts::PI;
/// Servo ID of the grasp hand's (symmetric) finger servo.
pub const SERVO_ID: u8 = 1;

/// How long the crush force must be exceeded before the object is damaged, s (assumed: paper
/// and foam creep; an impact peak of milliseconds does not crush them).
pub const CRUSH_TIME_S: f64 = 0.5;
/// Slide along the pad beyond which a hold counts as slipped, m (0.1 mm).
pub const SLIP_TOLERANCE_M: f64 = 1e-4;
/// The largest step the rig accepts, s.
pub const MAX_DT_S: f64 = 1.0;

/// The hand around the object.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RigParams {
    /// Finger lever and efficiency.
    pub linkage: Linkage,
    /// Servo gains, profile speed and the mechanics it carries.
    pub servo: ServoTuning,
    /// Pad-to-surface distance at the start, m.
    pub approach_m: f64,
    /// How far past first contact [`GraspRig::close`] sends each pad, m. Position control under
    /// a torque limit (§5) needs a goal inside the object; 15 mm saturates the P controller on a
    /// rigid object at any limit, while a soft one (cone, paper cup) lets the servo arrive.
    pub goal_squeeze_m: f64,
    /// Damping ratio of the pad–object contact (silicone skin losses, assumed).
    pub contact_damping_ratio: f64,
}

impl Default for RigParams {
    fn default() -> Self {
        RigParams {
            linkage: Linkage::default(),
            servo: ServoTuning::default(),
            approach_m: 0.005,
            goal_squeeze_m: 0.015,
            contact_damping_ratio: 0.3,
        }
    }
}

impl RigParams {
    /// The closing angle that puts each pad `squeeze_m` past first contact, rad.
    pub fn goal_for_squeeze_rad(&self, squeeze_m: f64) -> f64 {
        (self.approach_m + squeeze_m) / self.linkage.lever_m
    }

    /// Checks every value.
    pub fn validate(&self) -> Result<(), SimError> {
        self.servo.validate()?;
        positive("lever_m", self.linkage.lever_m)?;
        positive("efficiency", self.linkage.efficiency)?;
        positive("goal_squeeze_m", self.goal_squeeze_m)?;
        positive("contact_damping_ratio", self.contact_damping_ratio)?;
        if !(self.approach_m.is_finite() && self.approach_m >= 0.0) {
            return Err(SimError::config("approach_m", "finite and ≥ 0"));
        }
        Ok(())
    }
}

/// Everything one step exposes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GraspState {
    /// Simulated time since the rig was built, s.
    pub t_s: f64,
    /// Servo present position, rad (0 at the start, positive closing).
    pub position_rad: f64,
    /// Servo present velocity, rad/s.
    pub velocity_rad_s: f64,
    /// Servo present load, signed fraction of the stall torque.
    pub load_fraction: f64,
    /// Motor current, A.
    pub current_a: f64,
    /// Torque limit in force, counts.
    pub torque_limit: u16,
    /// Whether the servo's torque is on.
    pub torque_enabled: bool,
    /// Hardware-error flags (overload).
    pub faults: Faults,
    /// Normal force of each pad on the object, N.
    pub grip_force_n: f64,
    /// Whether the object is sliding now.
    pub slipping: bool,
    /// Total slide along the pads since the lift, m.
    pub slip_m: f64,
    /// Whether the object has been crushed.
    pub damaged: bool,
    /// Whether the object has left the grasp (slid off the pads).
    pub dropped: bool,
    /// Where and how hard the object presses each fingertip pad.
    pub patch: ContactPatch,
}

impl GraspState {
    /// The state of `body` squeezed by `servo`, wherever the servo runs (in process or on the
    /// bus simulator). The torque limit is read back from Goal PWM on the paper's 0…1023 scale.
    pub fn of(servo: &SimServo, body: &GraspBody) -> GraspState {
        let pwm = f64::from(servo.get(MX_28.goal_effort.address));
        let full = f64::from(MX_28.effort_limit.default);
        GraspState {
            t_s: servo.now().as_secs_f64(),
            position_rad: body.closing_rad(servo.position_rad()),
            velocity_rad_s: servo.velocity_rad_s(),
            load_fraction: servo.load_fraction(),
            current_a: servo.current_a(),
            torque_limit: (pwm / full * f64::from(TORQUE_LIMIT_MAX)).round() as u16,
            torque_enabled: servo.torque_enabled(),
            faults: hand_control::faults_from_hardware_error(servo.hardware_error()),
            grip_force_n: body.grip_force_n(),
            slipping: body.slipping(),
            slip_m: body.slip_m(),
            damaged: body.damaged(),
            dropped: body.dropped(),
            patch: body.patch(),
        }
    }
}

/// One object between two MX-28 fingers.
#[derive(Debug)]
pub struct GraspRig {
    plant: GraspPlant,
    servo: SimServo,
    torque_limit: u16,
    t: Duration,
    steps: u64,
}

/// A register write the rig makes, as the servo would answer it.
fn write(servo: &mut SimServo, name: &'static str, value: i32) -> Result<(), SimError> {
    let reg = MX_28
        .register(name)
        .ok_or_else(|| SimError::config(name, "not an MX-28(2.0) register"))?;
    let bytes = reg.encode(value);
    servo
        .write(reg.address, &bytes[..usize::from(reg.width)])
        .map_err(|e| SimError::config(name, format!("{value} refused: {e:?}")))
}

impl GraspRig {
    /// A rig with open fingers `approach_m` from `object`, goal at the start, limit 1023,
    /// torque on.
    pub fn new(object: ObjectParams, params: RigParams) -> Result<GraspRig, SimError> {
        object.validate()?;
        params.validate()?;
        let plant = GraspPlant::new(GraspBody::new(object, params, ORIGIN_RAD));
        let mut servo = SimServo::new(SERVO_ID, ORIGIN_RAD, params.servo.params());
        servo.set_plant(Some(Box::new(plant.clone())));
        let mut rig = GraspRig {
            plant,
            servo,
            torque_limit: TORQUE_LIMIT_MAX,
            t: Duration::ZERO,
            steps: 0,
        };
        rig.configure()?;
        rig.set_torque_limit(TORQUE_LIMIT_MAX)?;
        rig.set_torque_enabled(true)?;
        Ok(rig)
    }

    /// Writes the tuning's RAM registers (again after a reboot, as a driver must).
    fn configure(&mut self) -> Result<(), SimError> {
        let tuning = self.plant.body().params().servo;
        for (name, value) in tuning.registers() {
            write(&mut self.servo, name, value)?;
        }
        Ok(())
    }

    /// Sets the torque limit, 0…1023 (§7), sent as the MX-28(2.0)'s Goal PWM; more is a typed
    /// error.
    pub fn set_torque_limit(&mut self, count: u16) -> Result<(), SimError> {
        if count > TORQUE_LIMIT_MAX {
            return Err(SimError::config(
                "torque_limit",
                format!("0…{TORQUE_LIMIT_MAX}, got {count}"),
            ));
        }
        let pwm = MX_28.effort_raw(f32::from(count) / f32::from(TORQUE_LIMIT_MAX));
        write(&mut self.servo, "Goal PWM", pwm)?;
        self.torque_limit = count;
        Ok(())
    }

    /// Sets the servo goal, rad from the start (positive closes).
    pub fn set_goal_rad(&mut self, goal_rad: f64) -> Result<(), SimError> {
        if !goal_rad.is_finite() {
            return Err(SimError::config("goal_rad", "finite"));
        }
        let raw = ((ORIGIN_RAD + goal_rad) / f64::from(MX_28.position_unit_rad)).round();
        write(&mut self.servo, "Goal Position", raw as i32)
    }

    /// The goal that puts each pad `squeeze_m` past first contact, rad.
    pub fn goal_for_squeeze_rad(&self, squeeze_m: f64) -> f64 {
        self.plant.body().params().goal_for_squeeze_rad(squeeze_m)
    }

    /// Closes: goal `goal_squeeze_m` past first contact.
    pub fn close(&mut self) -> Result<(), SimError> {
        let squeeze = self.plant.body().params().goal_squeeze_m;
        self.set_goal_rad(self.goal_for_squeeze_rad(squeeze))
    }

    /// Lifts (`true`): from now on gravity pulls the object along the pads and only friction
    /// holds it; `false` puts it back on the table.
    pub fn set_lifted(&mut self, lifted: bool) {
        let at = if lifted { 0.0 } else { f64::INFINITY };
        self.plant.body().lift_at(at);
    }

    /// Servo torque on / off (on is refused while the overload bit is set).
    pub fn set_torque_enabled(&mut self, on: bool) -> Result<(), SimError> {
        write(&mut self.servo, "Torque Enable", i32::from(on))
    }

    /// The servo's REBOOT: clears the overload bit, torque off; the rig restores its RAM
    /// settings (gains, profile, limit) as a driver does.
    pub fn reboot(&mut self) -> Result<(), SimError> {
        self.servo.reboot();
        self.configure()?;
        self.set_torque_limit(self.torque_limit)
    }

    /// Advances by `dt_s` (0 < dt ≤ 1 s) and returns the new state.
    pub fn step(&mut self, dt_s: f64) -> Result<GraspState, SimError> {
        if !(dt_s.is_finite() && dt_s > 0.0 && dt_s <= MAX_DT_S) {
            return Err(SimError::config(
                "dt",
                format!("0 < dt ≤ {MAX_DT_S} s, got {dt_s}"),
            ));
        }
        let dt = Duration::from_secs_f64(dt_s);
        self.t += dt;
        self.servo.step(dt, self.t);
        self.steps += 1;
        Ok(self.state())
    }

    /// The present state.
    pub fn state(&self) -> GraspState {
        GraspState {
            // The count asked for (Goal PWM's coarser scale may not read back to the same one).
            torque_limit: self.torque_limit,
            ..GraspState::of(&self.servo, &self.plant.body())
        }
    }

    /// The servo, for its register-level readouts (Present Position, Present Load).
    pub fn servo(&self) -> &SimServo {
        &self.servo
    }

    /// The object and its state.
    pub fn body(&self) -> std::sync::MutexGuard<'_, GraspBody> {
        self.plant.body()
    }

    /// Steps taken since built.
    pub fn steps(&self) -> u64 {
        self.steps
    }
}
