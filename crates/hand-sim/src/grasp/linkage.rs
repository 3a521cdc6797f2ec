//! From the MX-28 torque-limit counts to fingertip force: the gear / finger lever.
//!
//! The paper gives the servo (MX-28, 12 V, Table 4) and the 0…1023 torque-limit scale (§7), not
//! the finger geometry. We assume each of the two opposing fingers is driven by its own MX-28
//! (same limit, same goal: the grasp is symmetric) through a finger of lever `lever_m` from the
//! servo axis to the pad, with a linkage efficiency `efficiency` (bearings, pad wrap, the servo
//! horn). At stall the MX-28's torque limit caps the PWM duty at `count / 1023`, so the output
//! torque is `count / 1023 · τ_stall` (e-manual: "Torque Limit … 1023 = 100 % of max torque"), and
//!
//! ```text
//! F_pad(count) = count / 1023 · τ_stall · η / L      (per finger, newton)
//! ```
//!
//! With τ_stall = 2.5 N·m (MX-28 e-manual, 12 V), η = 0.6 and L = 100 mm, 1023 counts press
//! 15 N per finger: a light hand, as the paper's sub-newton holding forces for small objects imply.

use serde::{Deserialize, Serialize};

use dxl_sim::MX28_STALL_TORQUE_NM as STALL_TORQUE_NM;

use super::servo::TORQUE_LIMIT_MAX;

/// The finger lever between servo and pad.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Linkage {
    /// Servo axis to pad centre, metre (assumed; the paper gives no finger dimensions).
    pub lever_m: f64,
    /// Fraction of the servo's output torque that reaches the pad (assumed).
    pub efficiency: f64,
}

impl Default for Linkage {
    fn default() -> Self {
        Linkage {
            lever_m: 0.100,
            efficiency: 0.6,
        }
    }
}

impl Linkage {
    /// Pad force per newton-metre of servo output torque, N/(N·m).
    pub fn force_per_torque(&self) -> f64 {
        self.efficiency / self.lever_m
    }

    /// The largest pad force the servo can press (torque limit 1023, stalled), newton.
    pub fn max_force_n(&self) -> f64 {
        STALL_TORQUE_NM * self.force_per_torque()
    }

    /// Stalled pad force at a torque limit of `count` (fractional counts allowed), newton.
    pub fn force_at_limit(&self, count: f64) -> f64 {
        count / f64::from(TORQUE_LIMIT_MAX) * self.max_force_n()
    }

    /// The torque-limit count (fractional) whose stalled pad force is `force_n`.
    pub fn limit_for_force(&self, force_n: f64) -> f64 {
        force_n / self.max_force_n() * f64::from(TORQUE_LIMIT_MAX)
    }
}
