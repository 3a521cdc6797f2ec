//! The settled grasp, in closed form: what force a torque limit ends up pressing, and which
//! limits therefore hold an object. Used to derive parameters from Table 5 and to give the
//! randomised objects their holding range; the simulated sweep ([`super::hold`]) measures the
//! same edges dynamically.

use serde::Serialize;

use super::object::{G, ObjectParams};
use super::rig::RigParams;
use super::servo::TORQUE_LIMIT_MAX;

/// A range of torque-limit counts that hold an object (inclusive).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct HoldingRange {
    /// Least count that holds without slip.
    pub min: u16,
    /// Greatest count that holds without damage, overload or release.
    pub max: u16,
}

/// The pad force at which the servo reaches equilibrium short of saturation: the P controller
/// pushing toward the goal (`goal_squeeze_m` past first contact per finger) against the object's
/// squeeze stiffness. `A = Kp · F_max / L` is the controller's stiffness at the pad; with pad
/// penetration `x`, `F = A (s − x)` and `F = 2 k x` give `F = A s / (1 + A / 2k)`.
pub fn goal_force_n(obj: &ObjectParams, rig: &RigParams) -> f64 {
    let a = rig.servo.kp_duty_per_rad() * rig.linkage.max_force_n() / rig.linkage.lever_m;
    let two_k = 2.0 * obj.material.stiffness_n_per_m;
    a * rig.goal_squeeze_m / (1.0 + a / two_k)
}

/// Settled pad force at a torque limit of `count`: the stalled force, or the goal force if the
/// servo reaches its goal first.
pub fn settled_force_n(count: f64, obj: &ObjectParams, rig: &RigParams) -> f64 {
    rig.linkage
        .force_at_limit(count)
        .min(goal_force_n(obj, rig))
}

/// The settled outcome at `count`: (slips, crushed, overloads).
pub fn settled_failures(count: u16, obj: &ObjectParams, rig: &RigParams) -> (bool, bool, bool) {
    let f = settled_force_n(f64::from(count), obj, rig);
    let slips = 2.0 * obj.material.friction * f < obj.mass_kg * G;
    let crushed = f >= obj.damage_force_n;
    let overloads = f / rig.linkage.max_force_n() >= rig.servo.params().overload_threshold;
    (slips, crushed, overloads)
}

/// The counts that hold `obj` in the settled state, if any.
pub fn predicted_range(obj: &ObjectParams, rig: &RigParams) -> Option<HoldingRange> {
    let holds = |c: u16| settled_failures(c, obj, rig) == (false, false, false);
    let min = (0..=TORQUE_LIMIT_MAX).find(|&c| !settled_failures(c, obj, rig).0)?;
    if !holds(min) {
        return None;
    }
    let max = (min..=TORQUE_LIMIT_MAX)
        .take_while(|&c| holds(c))
        .last()
        .unwrap_or(min);
    Some(HoldingRange { min, max })
}
