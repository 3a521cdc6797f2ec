//! The `[grasp]` table of a scene file.
//!
//! ```toml
//! [grasp]
//! objects = ["cube", "paper_cup", "random:3"]  # default: the six of Table 5
//! torque_limit = 240        # default: the middle of each object's holding range
//! schedule = [{ at_s = 60.0, torque_limit = 100 }]   # limit changes during the run
//! dt_s = 0.001
//! lift_at_s = 3.0
//! duration_s = 123.0        # close, lift at 3 s, hold 2 min (Table 5)
//! [grasp.rig]               # the hand; every key optional
//! goal_squeeze_m = 0.015
//! ```

use serde::Deserialize;

use super::object::ObjectKind;
use super::rig::{MAX_DT_S, RigParams};
use super::servo::{TORQUE_LIMIT_MAX, positive};
use crate::SimError;

/// What the grasp model runs.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct GraspConfig {
    /// The objects, each grasped by its own hand.
    pub objects: Vec<ObjectChoice>,
    /// Torque limit, counts; `None`: the middle of each object's predicted holding range.
    pub torque_limit: Option<u16>,
    /// Torque-limit changes, applied in time order.
    pub schedule: Vec<TorqueStep>,
    /// Fixed step, s.
    pub dt_s: f64,
    /// When the object is lifted, s.
    pub lift_at_s: f64,
    /// When the run ends (later steps are not taken), s.
    pub duration_s: f64,
    /// The hand.
    pub rig: RigParams,
}

impl Default for GraspConfig {
    fn default() -> Self {
        GraspConfig {
            objects: ObjectKind::ALL.map(ObjectChoice::Table5).to_vec(),
            torque_limit: None,
            schedule: Vec::new(),
            dt_s: 1e-3,
            lift_at_s: 3.0,
            duration_s: 123.0,
            rig: RigParams::default(),
        }
    }
}

impl GraspConfig {
    /// Checks every value.
    pub fn validate(&self) -> Result<(), SimError> {
        let limits = self
            .torque_limit
            .into_iter()
            .chain(self.schedule.iter().map(|s| s.torque_limit));
        for l in limits {
            if l > TORQUE_LIMIT_MAX {
                return Err(SimError::config("torque_limit", format!("0…1023, got {l}")));
            }
        }
        if self.schedule.iter().any(|s| !s.at_s.is_finite()) {
            return Err(SimError::config("schedule.at_s", "finite"));
        }
        if positive("dt_s", self.dt_s)? > MAX_DT_S {
            return Err(SimError::config("dt_s", format!("at most {MAX_DT_S} s")));
        }
        positive("duration_s", self.duration_s)?;
        if !self.lift_at_s.is_finite() {
            return Err(SimError::config("lift_at_s", "finite"));
        }
        self.rig.validate()
    }
}

/// A torque-limit change at a time.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TorqueStep {
    /// When, s.
    pub at_s: f64,
    /// The new limit, counts.
    pub torque_limit: u16,
}

/// An object in a scene: a Table 5 object by name, or `"random:<i>"`, the `i`-th randomised
/// object of the scene seed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(try_from = "String")]
pub enum ObjectChoice {
    /// One of the six.
    Table5(ObjectKind),
    /// The `i`-th of [`super::random_objects`].
    Random(u16),
}

impl TryFrom<String> for ObjectChoice {
    type Error = String;

    fn try_from(s: String) -> Result<Self, Self::Error> {
        if let Some(kind) = ObjectKind::from_name(&s) {
            return Ok(ObjectChoice::Table5(kind));
        }
        s.strip_prefix("random:")
            .and_then(|i| i.parse().ok())
            .map(ObjectChoice::Random)
            .ok_or_else(|| format!("unknown object {s:?}: a Table 5 name or \"random:<0…65535>\""))
    }
}
