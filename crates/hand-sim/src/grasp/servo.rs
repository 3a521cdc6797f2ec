//! How the grasp hand tunes its MX-28s, and the paper's torque-limit scale.
//!
//! The motor itself is not modelled here: the one MX-28 of the workspace is
//! [`dxl_sim::SimServo`] (e-Manual constants cited there once), and the grasp physics
//! drives it through its [`dxl_sim::Plant`] ([`super::plant::GraspPlant`]), in process
//! ([`super::GraspRig`]) or behind the Protocol 2.0 bus simulator.
//!
//! Seed 000 §5: "to control the grasping force with the given output torque values, position
//! control is implemented"; §7: the limit runs 0 (0 %)…1023 (100 %), the Protocol 1.0 Torque
//! Limit. On the MX-28(2.0) the same fraction is Goal PWM 0…885 ([`MX_28`]`.effort_raw`).

use dxl_sim::ServoParams;
use hand_control::control_table::MX_28;
use serde::{Deserialize, Serialize};

use crate::SimError;

/// Top of the paper's torque-limit scale (§7: 1023 = 100 %), hand-traits' own.
pub const TORQUE_LIMIT_MAX: u16 = hand_traits::Effort::TORQUE_LIMIT_RAW_MAX;

/// The RAM settings and the assumed mechanics of the grasp hand's servos.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ServoTuning {
    /// Position P Gain (MX-28(2.0) register 84, `K_PP = P / 128` PWM units per position unit).
    /// The factory 850 would need a 40 mm overshoot of the goal to saturate at the pad; the paper
    /// gives no gains: we take 1772, the Protocol 1.0 P gain 128 (`Kp = P / 8` of 1023) on the 2.0
    /// scale.
    pub p_gain: u16,
    /// Profile Velocity (register 112, 0.229 rev/min units): how fast the set-point moves toward
    /// the goal. 8 ≈ 0.19 rad/s.
    pub profile_velocity: u16,
    /// Rotor through the 193:1 gear plus finger, referred to the output, kg·m² (assumed).
    pub inertia_kg_m2: f64,
    /// Viscous gear friction at the output, N·m·s/rad (assumed).
    pub gear_friction_nm_s: f64,
}

impl Default for ServoTuning {
    fn default() -> Self {
        ServoTuning {
            p_gain: 1772,
            profile_velocity: 8,
            inertia_kg_m2: 2.0e-3,
            gear_friction_nm_s: 0.01,
        }
    }
}

impl ServoTuning {
    /// The P gain as duty (fraction of full PWM) per radian of position error.
    pub fn kp_duty_per_rad(&self) -> f64 {
        let pwm_full = f64::from(MX_28.effort_limit.default);
        f64::from(self.p_gain) / 128.0 / pwm_full / f64::from(MX_28.position_unit_rad)
    }

    /// The motor with this tuning's mechanics (the rest: the MX-28's e-Manual constants).
    pub fn params(&self) -> ServoParams {
        ServoParams {
            inertia_kg_m2: self.inertia_kg_m2,
            gear_friction_nm_s: self.gear_friction_nm_s,
            ..ServoParams::default()
        }
    }

    /// The RAM registers to write (name, value) before a grasp, and again after a reboot.
    pub fn registers(&self) -> [(&'static str, i32); 2] {
        [
            ("Position P Gain", i32::from(self.p_gain)),
            ("Profile Velocity", i32::from(self.profile_velocity)),
        ]
    }

    /// Checks every value.
    pub fn validate(&self) -> Result<(), SimError> {
        positive("inertia_kg_m2", self.inertia_kg_m2)?;
        if !(self.gear_friction_nm_s.is_finite() && self.gear_friction_nm_s >= 0.0) {
            return Err(SimError::config("gear_friction_nm_s", "finite and ≥ 0"));
        }
        for (name, value) in self.registers() {
            let ok = MX_28.register(name).is_some_and(|r| r.in_range(value));
            if !ok {
                return Err(SimError::config(
                    name,
                    format!("outside the MX-28(2.0) range: {value}"),
                ));
            }
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
