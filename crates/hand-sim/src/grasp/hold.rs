//! The hold test behind Table 5 and the sweep that measures an object's holding range in the
//! simulator: close under a torque limit, lift, hold (Table 5 caption: "more than 2 min").

use serde::{Deserialize, Serialize};

use super::object::ObjectParams;
use super::rig::{GraspRig, RigParams, SLIP_TOLERANCE_M};
use super::servo::TORQUE_LIMIT_MAX;
use super::statics::HoldingRange;
use crate::SimError;

/// One hold: close at t = 0, lift at `lift_at_s`, hold `hold_s` more.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct HoldTest {
    /// Step, s.
    pub dt_s: f64,
    /// When the arm lifts the object off the table, s (the grip has settled by then).
    pub lift_at_s: f64,
    /// How long the lifted object is held, s (Table 5: 2 min).
    pub hold_s: f64,
}

impl Default for HoldTest {
    fn default() -> Self {
        HoldTest {
            dt_s: 1e-3,
            lift_at_s: 3.0,
            hold_s: 120.0,
        }
    }
}

/// How a hold ended.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct HoldOutcome {
    /// The torque limit, counts.
    pub torque_limit: u16,
    /// Slid more than [`SLIP_TOLERANCE_M`] along the pads.
    pub slipped: bool,
    /// Crushed.
    pub damaged: bool,
    /// The servo's overload bit tripped (and torque went off).
    pub overloaded: bool,
    /// The object left the grasp.
    pub dropped: bool,
    /// Pad force at the end, N.
    pub final_force_n: f64,
    /// Largest pad force during the hold, N.
    pub peak_force_n: f64,
    /// Motor current at the end, A.
    pub final_current_a: f64,
}

impl HoldOutcome {
    /// Held for the whole test without slip, damage, overload or release.
    pub fn held(&self) -> bool {
        !(self.slipped || self.damaged || self.overloaded || self.dropped)
    }
}

/// Runs one hold of `object` at `torque_limit`, calling `each` with every step's state.
pub fn run_hold_with(
    object: &ObjectParams,
    rig: &RigParams,
    torque_limit: u16,
    test: &HoldTest,
    mut each: impl FnMut(&super::GraspState),
) -> Result<HoldOutcome, SimError> {
    let mut g = GraspRig::new(object.clone(), *rig)?;
    g.set_torque_limit(torque_limit)?;
    g.close()?;
    let steps = ((test.lift_at_s + test.hold_s) / test.dt_s).ceil();
    if !(1.0..=1e9).contains(&steps) {
        return Err(SimError::config("hold_s", "1 … 1e9 steps of dt_s"));
    }
    let mut peak = 0.0_f64;
    let mut s = g.state();
    for _ in 0..steps as u64 {
        if s.t_s >= test.lift_at_s {
            g.set_lifted(true);
        }
        s = g.step(test.dt_s)?;
        peak = peak.max(s.grip_force_n);
        each(&s);
    }
    Ok(HoldOutcome {
        torque_limit,
        slipped: s.slip_m > SLIP_TOLERANCE_M,
        damaged: s.damaged,
        overloaded: !s.faults.is_empty(),
        dropped: s.dropped,
        final_force_n: s.grip_force_n,
        peak_force_n: peak,
        final_current_a: s.current_a,
    })
}

/// Runs one hold of `object` at `torque_limit`.
pub fn run_hold(
    object: &ObjectParams,
    rig: &RigParams,
    torque_limit: u16,
    test: &HoldTest,
) -> Result<HoldOutcome, SimError> {
    run_hold_with(object, rig, torque_limit, test, |_| {})
}

/// Measures the holding range by bisection on simulated holds: the least limit that does not
/// slip, then the greatest limit above it that holds. Assumes (as the physics gives) that slip
/// only gets less likely and damage / overload only more likely as the limit rises.
pub fn sweep_holding_range(
    object: &ObjectParams,
    rig: &RigParams,
    test: &HoldTest,
) -> Result<Option<HoldingRange>, SimError> {
    let hold = |c: u16| run_hold(object, rig, c, test);
    // Least c in lo..=hi with pred(c), given pred(hi) and monotone pred.
    fn least(
        mut lo: u16,
        mut hi: u16,
        pred: &dyn Fn(u16) -> Result<bool, SimError>,
    ) -> Result<u16, SimError> {
        while lo < hi {
            let mid = lo + (hi - lo) / 2;
            if pred(mid)? {
                hi = mid;
            } else {
                lo = mid + 1;
            }
        }
        Ok(lo)
    }
    // A release after an overload also ends in a slide; the friction edge is about the others.
    let grips = |c: u16| hold(c).map(|o| !o.slipped || o.overloaded);
    if !grips(TORQUE_LIMIT_MAX)? {
        return Ok(None);
    }
    let min = least(0, TORQUE_LIMIT_MAX, &grips)?;
    if !hold(min)?.held() {
        return Ok(None);
    }
    if hold(TORQUE_LIMIT_MAX)?.held() {
        return Ok(Some(HoldingRange {
            min,
            max: TORQUE_LIMIT_MAX,
        }));
    }
    let first_fail = least(min, TORQUE_LIMIT_MAX, &|c| Ok(!hold(c)?.held()))?;
    Ok(Some(HoldingRange {
        min,
        max: first_fail - 1,
    }))
}
