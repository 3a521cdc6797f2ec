//! One grasp: two opposing fingers, each on an MX-28, squeezing one object, then lifting it.
//! The plain API the control loop (issue 9) drives: set the torque limit and goal, step, read.

use hand_traits::Faults;
use serde::{Deserialize, Serialize};

use super::contact::{self, PAD_SLIDE_LIMIT_M};
use super::linkage::Linkage;
use super::object::{G, ObjectParams};
use super::persist::Persistence;
use super::servo::{Mx28, ServoParams, positive};
use crate::SimError;
use crate::fingertip::ContactPatch;

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
    /// Servo gains, speed and inertia.
    pub servo: ServoParams,
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
            servo: ServoParams::default(),
            approach_m: 0.005,
            goal_squeeze_m: 0.015,
            contact_damping_ratio: 0.3,
        }
    }
}

impl RigParams {
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

/// One object between two MX-28 fingers.
#[derive(Debug, Clone)]
pub struct GraspRig {
    object: ObjectParams,
    params: RigParams,
    servo: Mx28,
    t_s: f64,
    lifted: bool,
    slide_v: f64,
    slip_m: f64,
    crush: Persistence,
    dropped: bool,
    force_n: f64,
    steps: u64,
}

impl GraspRig {
    /// A rig with open fingers `approach_m` from `object`, goal at the start, limit 1023.
    pub fn new(object: ObjectParams, params: RigParams) -> Result<GraspRig, SimError> {
        object.validate()?;
        params.validate()?;
        Ok(GraspRig {
            servo: Mx28::new(params.servo)?,
            object,
            params,
            t_s: 0.0,
            lifted: false,
            slide_v: 0.0,
            slip_m: 0.0,
            crush: Persistence::default(),
            dropped: false,
            force_n: 0.0,
            steps: 0,
        })
    }

    /// Sets the torque limit, 0…1023; more is a typed error.
    pub fn set_torque_limit(&mut self, count: u16) -> Result<(), SimError> {
        self.servo.set_torque_limit(count)
    }

    /// Sets the servo goal, rad.
    pub fn set_goal_rad(&mut self, goal_rad: f64) -> Result<(), SimError> {
        self.servo.set_goal_rad(goal_rad)
    }

    /// The goal that puts each pad `squeeze_m` past first contact, rad.
    pub fn goal_for_squeeze_rad(&self, squeeze_m: f64) -> f64 {
        (self.params.approach_m + squeeze_m) / self.params.linkage.lever_m
    }

    /// Closes: goal `goal_squeeze_m` past first contact.
    pub fn close(&mut self) -> Result<(), SimError> {
        self.set_goal_rad(self.goal_for_squeeze_rad(self.params.goal_squeeze_m))
    }

    /// Lifts (`true`): from now on gravity pulls the object along the pads and only friction
    /// holds it; `false` puts it back on the table.
    pub fn set_lifted(&mut self, lifted: bool) {
        self.lifted = lifted;
    }

    /// Servo torque on / off (on is refused while the overload bit is set).
    pub fn set_torque_enabled(&mut self, on: bool) -> Result<(), SimError> {
        self.servo.set_torque_enabled(on)
    }

    /// The servo's REBOOT: clears the overload bit, torque off.
    pub fn reboot(&mut self) {
        self.servo.reboot();
    }

    /// Advances by `dt_s` (0 < dt ≤ 1 s) and returns the new state.
    pub fn step(&mut self, dt_s: f64) -> Result<GraspState, SimError> {
        if !(dt_s.is_finite() && dt_s > 0.0 && dt_s <= MAX_DT_S) {
            return Err(SimError::config(
                "dt",
                format!("0 < dt ≤ {MAX_DT_S} s, got {dt_s}"),
            ));
        }
        let lin = |theta| {
            if self.dropped {
                Default::default()
            } else {
                contact::load(theta, &self.object, &self.params)
            }
        };
        self.servo.step(dt_s, lin(self.servo.position_rad()));
        let after = lin(self.servo.position_rad());
        self.force_n = contact::pad_force_n(&after, self.servo.velocity_rad_s(), &self.params);
        self.crush.update(
            self.force_n >= self.object.damage_force_n,
            dt_s,
            CRUSH_TIME_S,
        );
        self.slide(dt_s);
        self.t_s += dt_s;
        self.steps += 1;
        Ok(self.state())
    }

    /// Gravity against Coulomb friction on both pads (µ static = µ kinetic): the object sticks
    /// while `2 µ F ≥ m g`, else slides down with `a = g − 2 µ F / m` until it stops or leaves
    /// the pads.
    fn slide(&mut self, dt_s: f64) {
        if !self.lifted || self.dropped {
            return;
        }
        let friction_n = 2.0 * self.object.material.friction * self.force_n;
        let weight_n = self.object.mass_kg * G;
        if self.slide_v == 0.0 && friction_n >= weight_n {
            return;
        }
        let a = G - friction_n / self.object.mass_kg;
        let v0 = self.slide_v;
        self.slide_v = (v0 + a * dt_s).max(0.0);
        self.slip_m += 0.5 * (v0 + self.slide_v) * dt_s;
        if self.slip_m >= PAD_SLIDE_LIMIT_M {
            self.dropped = true;
            self.slide_v = 0.0;
            self.force_n = 0.0;
        }
    }

    /// The present state.
    pub fn state(&self) -> GraspState {
        GraspState {
            t_s: self.t_s,
            position_rad: self.servo.position_rad(),
            velocity_rad_s: self.servo.velocity_rad_s(),
            load_fraction: self.servo.load_fraction(),
            current_a: self.servo.current_a(),
            torque_limit: self.servo.torque_limit(),
            torque_enabled: self.servo.torque_enabled(),
            faults: self.servo.faults(),
            grip_force_n: self.force_n,
            slipping: self.slide_v > 0.0,
            slip_m: self.slip_m,
            damaged: self.crush.tripped(),
            dropped: self.dropped,
            patch: if self.dropped {
                ContactPatch::NONE
            } else {
                contact::patch(&self.object, self.force_n)
            },
        }
    }

    /// The servo, for its register-level readouts (ticks, raw load).
    pub fn servo(&self) -> &Mx28 {
        &self.servo
    }

    /// The object.
    pub fn object(&self) -> &ObjectParams {
        &self.object
    }

    /// The hand's parameters.
    pub fn params(&self) -> &RigParams {
        &self.params
    }

    /// Steps taken since built.
    pub fn steps(&self) -> u64 {
        self.steps
    }
}
