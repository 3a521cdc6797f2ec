//! One two-phalanx finger, quasi-static: tendon tension against joint springs, joint stops and
//! contact forces.
//!
//! Stated model: a tendon over pulleys of radius `r₁` (proximal) and `r₂` (distal) with tension
//! `T` drives both pin joints; return springs with preload hold the distal straight until the
//! proximal meets resistance (so the proximal closes first, then the distal wraps). Joint
//! torque balance, contacts at `a₁` on the proximal and `a₂` (the FSR's centre) on the distal:
//!
//! ```text
//! distal:    T·r₂ = τ₂₀ + k₂·θ₂ + F₂·a₂
//! proximal:  T·r₁ = τ₁₀ + k₁·θ₁ + F₁·a₁ + F₂·(a₂ + l₁·cos θ₂)
//! ```
//!
//! Each joint stays within 0…90° (seed 001 §2.3); at a stop the stop takes the excess torque.
//! The distal contact depth uses the proximal angle of the previous step (operator splitting,
//! error of one 50 ms step of a 1.5 mm/s closing).

use super::contact::{ContactLaw, Pad};
use super::solve::increasing_root_near;
use serde::Deserialize;

/// A finger's geometry and springs; SI units. Defaults are a plausible finger (55 mm proximal) on a
/// 130 mm hand.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct FingerParams {
    /// Proximal phalanx length `l₁`, m.
    pub proximal_length_m: f64,
    /// Proximal contact point from its joint `a₁`, m.
    pub proximal_contact_m: f64,
    /// Distal contact point (FSR centre) from its joint `a₂`, m.
    pub distal_contact_m: f64,
    /// Tendon pulley radius at the proximal joint `r₁`, m.
    pub proximal_pulley_m: f64,
    /// Tendon pulley radius at the distal joint `r₂`, m.
    pub distal_pulley_m: f64,
    /// Proximal return spring `k₁`, N·m/rad.
    pub proximal_spring_nm_per_rad: f64,
    /// Distal return spring `k₂`, N·m/rad.
    pub distal_spring_nm_per_rad: f64,
    /// Proximal spring preload `τ₁₀`, N·m.
    pub proximal_preload_nm: f64,
    /// Distal spring preload `τ₂₀`, N·m.
    pub distal_preload_nm: f64,
    /// Distance from the hand's axis to each finger's base, m: objects up to twice this fit.
    pub palm_radius_m: f64,
    /// Mechanical limit of both joints, degrees (seed 001 §2.3: 90°).
    pub joint_limit_deg: f64,
    /// The soft fingertip pad.
    pub pad: Pad,
}

impl Default for FingerParams {
    fn default() -> Self {
        FingerParams {
            proximal_length_m: 0.055,
            proximal_contact_m: 0.040,
            distal_contact_m: 0.025,
            proximal_pulley_m: 0.015,
            distal_pulley_m: 0.0045,
            proximal_spring_nm_per_rad: 0.05,
            distal_spring_nm_per_rad: 0.03,
            proximal_preload_nm: 0.01,
            distal_preload_nm: 0.012,
            palm_radius_m: 0.065,
            joint_limit_deg: 90.0,
            pad: Pad::default(),
        }
    }
}

/// Where a finger meets the object and how the object pushes back there.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FingerContact {
    /// Proximal angle at which the proximal phalanx touches, rad.
    pub proximal_touch_rad: f64,
    /// Distal angle (relative to the proximal) at which the distal phalanx touches, rad.
    pub distal_touch_rad: f64,
    /// The proximal phalanx's contact law.
    pub proximal: ContactLaw,
    /// The distal phalanx's contact law.
    pub distal: ContactLaw,
}

/// A finger's quasi-static state.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct FingerState {
    /// Proximal joint angle, rad.
    pub proximal_rad: f64,
    /// Distal joint angle, rad (what the potentiometer reads).
    pub distal_rad: f64,
    /// Proximal contact force, N.
    pub proximal_force_n: f64,
    /// Distal contact force, N (what the FSR reads).
    pub distal_force_n: f64,
    /// Proximal and distal contact indentation, m.
    pub depth_m: [f64; 2],
}

const ANGLE_TOL: f64 = 1e-6;
/// First search half-width around the previous angle, rad.
const WARM_RAD: f64 = 0.02;

impl FingerParams {
    /// Tendon length the finger has taken up in `state`, m.
    pub fn tendon_travel(&self, state: &FingerState) -> f64 {
        self.proximal_pulley_m * state.proximal_rad + self.distal_pulley_m * state.distal_rad
    }

    /// The equilibrium under tendon tension `tension_n`, with `creep` (m) relaxed at each
    /// contact, starting the search from the `previous` step's state.
    pub fn equilibrium(
        &self,
        tension_n: f64,
        contact: Option<&FingerContact>,
        creep: [f64; 2],
        previous: &FingerState,
    ) -> FingerState {
        let previous_proximal_rad = previous.proximal_rad;
        let limit = self.joint_limit_deg.to_radians();
        let (a1, a2) = (self.proximal_contact_m, self.distal_contact_m);
        // Until the proximal reaches its touch angle the distal must turn that much further.
        let gap = contact.map_or(0.0, |c| {
            (c.proximal_touch_rad - previous_proximal_rad).max(0.0)
        });
        let distal_depth =
            |th2: f64| contact.map_or(0.0, |c| a2 * (th2 - c.distal_touch_rad - gap));
        let distal_force =
            |th2: f64| contact.map_or(0.0, |c| c.distal.force(distal_depth(th2), creep[1]));
        let th2 = increasing_root_near(
            |x| {
                self.distal_preload_nm + self.distal_spring_nm_per_rad * x + distal_force(x) * a2
                    - tension_n * self.distal_pulley_m
            },
            previous.distal_rad,
            WARM_RAD,
            0.0,
            limit,
            ANGLE_TOL,
        );
        let f2 = distal_force(th2);
        let moment2 = f2 * (a2 + self.proximal_length_m * th2.cos());
        let proximal_depth = |th1: f64| contact.map_or(0.0, |c| a1 * (th1 - c.proximal_touch_rad));
        let proximal_force =
            |th1: f64| contact.map_or(0.0, |c| c.proximal.force(proximal_depth(th1), creep[0]));
        let th1 = increasing_root_near(
            |x| {
                self.proximal_preload_nm
                    + self.proximal_spring_nm_per_rad * x
                    + proximal_force(x) * a1
                    + moment2
                    - tension_n * self.proximal_pulley_m
            },
            previous.proximal_rad,
            WARM_RAD,
            0.0,
            limit,
            ANGLE_TOL,
        );
        FingerState {
            proximal_rad: th1,
            distal_rad: th2,
            proximal_force_n: proximal_force(th1),
            distal_force_n: f2,
            depth_m: [proximal_depth(th1), distal_depth(th2)],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_free_finger_closes_proximal_first_and_stops_at_the_limits() {
        let p = FingerParams::default();
        let limit = p.joint_limit_deg.to_radians();
        let light = p.equilibrium(2.0, None, [0.0; 2], &FingerState::default());
        assert!(
            light.proximal_rad > 0.3 && light.distal_rad == 0.0,
            "{light:?}"
        );
        let heavy = p.equilibrium(1000.0, None, [0.0; 2], &FingerState::default());
        assert_eq!((heavy.proximal_rad, heavy.distal_rad), (limit, limit));
    }
}
