//! An MX-28-like servo: position control toward a goal under a torque limit 0…1023.
//!
//! Seed 000 §5: "to control the grasping force with the given output torque values, position
//! control is implemented"; §7: the limit runs 0 (0 %)…1023 (100 %). The model:
//!
//! - **Controller.** The set-point moves toward the goal at the moving speed (MX-28 joint mode,
//!   "Moving Speed"); the PWM duty is `Kp · (set-point − position)` with `Kp = P / 8` duty counts
//!   (of 1023) per encoder tick (e-manual: "Kp = P Gain / 8"; the output unit is our reading),
//!   clamped to `± limit / 1023` — the torque limit caps the output.
//! - **Motor and gear**, referred to the output shaft: a DC motor whose torque is
//!   `τ_stall · (duty − ω / ω_no-load)` and current `I_stall · (duty − ω / ω_no-load)` (so load
//!   and current are the same fraction), with τ_stall = 2.5 N·m, I_stall = 1.4 A and 67 rpm
//!   no-load at 12 V (MX-28 e-manual); reflected inertia and gear friction are assumptions.
//! - **Overload.** Hardware-error bit 5, "persistent load that exceeds maximum output"
//!   (e-manual); Alarm Shutdown's default (0x24) includes it, so torque goes off. The firmware's
//!   threshold and time are not published: we take |load| ≥ 90 % held for 1 s. A torque limit
//!   below 90 % can therefore never overload; 1023 overloads whenever the object resists at full
//!   output (§7), but not when a compliant object lets the servo reach its goal first (Table 5's
//!   1023 maxima) — see `docs/sim-calibration/grasp.md`.
//!
//! Integration is linearly implicit (controller spring, back-EMF, load stiffness and damping all
//! taken at the end of the step), so any positive stiffness and any step size stay bounded.

use hand_traits::Faults;
use serde::{Deserialize, Serialize};

use super::persist::Persistence;
use crate::SimError;

/// MX-28 stall torque at 12 V, N·m (e-manual).
pub const STALL_TORQUE_NM: f64 = 2.5;
/// MX-28 stall current at 12 V, A (e-manual).
pub const STALL_CURRENT_A: f64 = 1.4;
/// MX-28 no-load speed at 12 V, rad/s (67 rpm, e-manual).
pub const NO_LOAD_SPEED_RAD_S: f64 = 67.0 * core::f64::consts::TAU / 60.0;
/// Top of the torque-limit scale (§7: 1023 = 100 %).
pub const TORQUE_LIMIT_MAX: u16 = 1023;
/// Encoder ticks per output revolution (MX-28: 0…4095, 0.088°).
pub const TICKS_PER_REV: f64 = 4096.0;
/// |load| at or above which the overload timer runs (assumed; not published).
pub const OVERLOAD_LOAD_FRACTION: f64 = 0.9;
/// How long the load must stay there before the overload bit trips, s (assumed).
pub const OVERLOAD_TIME_S: f64 = 1.0;

/// The tunable part of the servo.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ServoParams {
    /// Position P gain on the MX-28 register scale 0…254 (`Kp = P / 8`). The factory 32 would
    /// need a 40 mm overshoot of the goal to saturate; the paper gives no gains, we take 128.
    pub p_gain: u8,
    /// How fast the set-point moves toward the goal, rad/s (MX-28 "Moving Speed").
    pub moving_speed_rad_s: f64,
    /// Rotor through the 193:1 gear plus finger, referred to the output, kg·m² (assumed).
    pub inertia_kg_m2: f64,
    /// Viscous gear friction at the output, N·m·s/rad (assumed).
    pub gear_friction_nm_s: f64,
}

impl Default for ServoParams {
    fn default() -> Self {
        ServoParams {
            p_gain: 128,
            moving_speed_rad_s: 0.2,
            inertia_kg_m2: 2.0e-3,
            gear_friction_nm_s: 0.01,
        }
    }
}

impl ServoParams {
    /// The P gain as duty (fraction of full PWM) per radian of position error.
    pub fn kp_duty_per_rad(&self) -> f64 {
        f64::from(self.p_gain) / 8.0 * TICKS_PER_REV
            / core::f64::consts::TAU
            / f64::from(TORQUE_LIMIT_MAX)
    }

    /// Checks that every value is finite and positive where it must be.
    pub fn validate(&self) -> Result<(), SimError> {
        positive("moving_speed_rad_s", self.moving_speed_rad_s)?;
        positive("inertia_kg_m2", self.inertia_kg_m2)?;
        if !(self.gear_friction_nm_s.is_finite() && self.gear_friction_nm_s >= 0.0) {
            return Err(SimError::config("gear_friction_nm_s", "finite and ≥ 0"));
        }
        Ok(())
    }
}

/// A finite, strictly positive value, or a typed error naming `field`.
pub(crate) fn positive(field: &'static str, v: f64) -> Result<f64, SimError> {
    if v.is_finite() && v > 0.0 {
        Ok(v)
    } else {
        Err(SimError::config(field, format!("finite and > 0, got {v}")))
    }
}

/// What the servo drives against, linearised at the present state: the load torque opposing
/// closing (spring part), its stiffness d τ / d θ and its damping d τ / d ω.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct LoadLinearisation {
    /// Load torque at the present position, spring part, N·m (positive opposes closing).
    pub torque_nm: f64,
    /// d τ / d θ, N·m/rad (≥ 0).
    pub stiffness_nm_per_rad: f64,
    /// d τ / d ω, N·m·s/rad (≥ 0).
    pub damping_nm_s_per_rad: f64,
}

/// The servo's state and controller.
#[derive(Debug, Clone, PartialEq)]
pub struct Mx28 {
    params: ServoParams,
    position_rad: f64,
    velocity_rad_s: f64,
    setpoint_rad: f64,
    goal_rad: f64,
    torque_limit: u16,
    torque_enabled: bool,
    faults: Faults,
    overload: Persistence,
    duty: f64,
}

impl Mx28 {
    /// A servo at rest at position 0, goal 0, full torque limit, torque enabled.
    pub fn new(params: ServoParams) -> Result<Mx28, SimError> {
        params.validate()?;
        Ok(Mx28 {
            params,
            position_rad: 0.0,
            velocity_rad_s: 0.0,
            setpoint_rad: 0.0,
            goal_rad: 0.0,
            torque_limit: TORQUE_LIMIT_MAX,
            torque_enabled: true,
            faults: Faults::NONE,
            overload: Persistence::default(),
            duty: 0.0,
        })
    }

    /// Sets the torque limit, 0…1023 (§7); above 1023 is a typed error, as the register is.
    pub fn set_torque_limit(&mut self, count: u16) -> Result<(), SimError> {
        if count > TORQUE_LIMIT_MAX {
            return Err(SimError::config(
                "torque_limit",
                format!("0…{TORQUE_LIMIT_MAX}, got {count}"),
            ));
        }
        self.torque_limit = count;
        Ok(())
    }

    /// Sets the goal position, rad (positive closes).
    pub fn set_goal_rad(&mut self, goal_rad: f64) -> Result<(), SimError> {
        if !goal_rad.is_finite() {
            return Err(SimError::config("goal_rad", "finite"));
        }
        self.goal_rad = goal_rad;
        Ok(())
    }

    /// Enables or disables torque. Enabling while the overload bit is set is refused, as on the
    /// servo (reboot first).
    pub fn set_torque_enabled(&mut self, on: bool) -> Result<(), SimError> {
        if on && !self.faults.is_empty() {
            return Err(SimError::config(
                "torque_enable",
                "hardware error set: reboot first",
            ));
        }
        if on && !self.torque_enabled {
            // The MX-28 starts holding where it is, not where the old set-point was.
            self.setpoint_rad = self.position_rad;
        }
        self.torque_enabled = on;
        Ok(())
    }

    /// The REBOOT instruction: clears the hardware error; torque stays off until enabled.
    pub fn reboot(&mut self) {
        self.faults = Faults::NONE;
        self.overload.reset();
        self.torque_enabled = false;
        self.duty = 0.0;
    }

    /// Advances by `dt_s` against `load`.
    pub fn step(&mut self, dt_s: f64, load: LoadLinearisation) {
        let p = self.params;
        let to_goal = self.goal_rad - self.setpoint_rad;
        let max_move = p.moving_speed_rad_s * dt_s;
        self.setpoint_rad += to_goal.clamp(-max_move, max_move);

        let (duty0, spring, emf) = if self.torque_enabled {
            let kp = p.kp_duty_per_rad();
            let raw = kp * (self.setpoint_rad - self.position_rad);
            let cap = self.limit_fraction();
            let saturated = raw.abs() > cap;
            let spring = if saturated { 0.0 } else { kp * STALL_TORQUE_NM };
            (
                raw.clamp(-cap, cap),
                spring,
                STALL_TORQUE_NM / NO_LOAD_SPEED_RAD_S,
            )
        } else {
            (0.0, 0.0, 0.0)
        };
        let lhs = p.inertia_kg_m2 / dt_s
            + (spring + load.stiffness_nm_per_rad) * dt_s
            + emf
            + load.damping_nm_s_per_rad
            + p.gear_friction_nm_s;
        let rhs =
            p.inertia_kg_m2 / dt_s * self.velocity_rad_s + STALL_TORQUE_NM * duty0 - load.torque_nm;
        self.velocity_rad_s = rhs / lhs;
        self.position_rad += self.velocity_rad_s * dt_s;

        self.duty = if self.torque_enabled {
            let kp = p.kp_duty_per_rad();
            let cap = self.limit_fraction();
            (kp * (self.setpoint_rad - self.position_rad)).clamp(-cap, cap)
        } else {
            0.0
        };
        let overloaded = self.overload.update(
            self.load_fraction().abs() >= OVERLOAD_LOAD_FRACTION,
            dt_s,
            OVERLOAD_TIME_S,
        );
        if overloaded {
            self.faults = self.faults.union(Faults::OVERLOAD);
            self.torque_enabled = false;
            self.duty = 0.0;
        }
    }

    fn limit_fraction(&self) -> f64 {
        f64::from(self.torque_limit) / f64::from(TORQUE_LIMIT_MAX)
    }

    /// Present position, rad.
    pub fn position_rad(&self) -> f64 {
        self.position_rad
    }

    /// Present position on the MX-28's 0…4095 scale (2048 = 0 rad), saturating.
    pub fn position_ticks(&self) -> u16 {
        let t = 2048.0 + self.position_rad * TICKS_PER_REV / core::f64::consts::TAU;
        t.round().clamp(0.0, TICKS_PER_REV - 1.0) as u16
    }

    /// Present velocity, rad/s.
    pub fn velocity_rad_s(&self) -> f64 {
        self.velocity_rad_s
    }

    /// Goal position, rad.
    pub fn goal_rad(&self) -> f64 {
        self.goal_rad
    }

    /// Torque limit, counts.
    pub fn torque_limit(&self) -> u16 {
        self.torque_limit
    }

    /// Whether torque is on.
    pub fn torque_enabled(&self) -> bool {
        self.torque_enabled
    }

    /// Hardware-error flags (overload).
    pub fn faults(&self) -> Faults {
        self.faults
    }

    /// Motor output torque as a signed fraction of the stall torque (positive closing): the
    /// MX-28's "Present Load".
    pub fn load_fraction(&self) -> f64 {
        if self.torque_enabled {
            self.duty - self.velocity_rad_s / NO_LOAD_SPEED_RAD_S
        } else {
            0.0
        }
    }

    /// Present Load as the MX-28 (Protocol 1.0) reports it: 0…1023 magnitude, bit 10 set when
    /// the load is in the opening (CW) direction.
    pub fn present_load_raw(&self) -> u16 {
        let l = self.load_fraction();
        let mag = (l.abs().min(1.0) * f64::from(TORQUE_LIMIT_MAX)).round() as u16;
        if l < 0.0 { mag | 1 << 10 } else { mag }
    }

    /// Motor current, A (signed, positive closing).
    pub fn current_a(&self) -> f64 {
        self.load_fraction() * STALL_CURRENT_A
    }

    /// Output torque of the motor, N·m.
    pub fn output_torque_nm(&self) -> f64 {
        self.load_fraction() * STALL_TORQUE_NM
    }
}
