//! What a grasp loop is told: its rate, pressure target, torque band, filter and safe state.

use hand_traits::{Effort, SafeAction};

use super::end::EndAction;

/// The torque-limit band a grasp may use, on the MX-28's 0…1023 scale (the grasping paper's §7).
///
/// Table 5 gives one per object: below `min_raw` the object slips, above `max_raw` it is crushed
/// or released. The loop clamps every effort into the band before it is sent.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct TorqueBand {
    min_raw: u16,
    max_raw: u16,
}

impl TorqueBand {
    /// The whole scale, 0…1023.
    pub const FULL: TorqueBand = TorqueBand {
        min_raw: 0,
        max_raw: Effort::TORQUE_LIMIT_RAW_MAX,
    };

    /// A band `min_raw..=max_raw`; an empty or off-scale band is a typed error.
    ///
    /// ```
    /// # use hand_control::grasp_loop::TorqueBand;
    /// let cube = TorqueBand::new(80, 400)?; // the grasping paper's Table 5
    /// assert_eq!(cube.clamp_raw(1023), 400);
    /// assert!(TorqueBand::new(400, 80).is_err());
    /// assert!(TorqueBand::new(0, 2000).is_err());
    /// # Ok::<(), hand_control::grasp_loop::ConfigError>(())
    /// ```
    pub fn new(min_raw: u16, max_raw: u16) -> Result<TorqueBand, ConfigError> {
        if min_raw > max_raw || max_raw > Effort::TORQUE_LIMIT_RAW_MAX {
            return Err(ConfigError::TorqueBand { min_raw, max_raw });
        }
        Ok(TorqueBand { min_raw, max_raw })
    }

    /// The least torque limit, counts.
    pub fn min_raw(self) -> u16 {
        self.min_raw
    }

    /// The greatest torque limit, counts.
    pub fn max_raw(self) -> u16 {
        self.max_raw
    }

    /// `raw` clamped into the band.
    pub fn clamp_raw(self, raw: u16) -> u16 {
        raw.clamp(self.min_raw, self.max_raw)
    }

    /// `effort` clamped into the band, and whether it had to be.
    pub fn clamp(self, effort: Effort) -> (Effort, bool) {
        let raw = effort.to_torque_limit_raw();
        let clamped = self.clamp_raw(raw);
        if clamped == raw {
            (effort, false)
        } else {
            (Effort::from_torque_limit_raw(clamped), true)
        }
    }
}

/// How the loop gets out of its safe state.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Recovery {
    /// Stay safe until the operator calls [`GraspLoop::resume`](super::GraspLoop::resume).
    Manual,
    /// Once the actuator answers again: resume at once if it reports no hardware error;
    /// otherwise, when its load has fallen under the configured fraction and `cooldown_us` has
    /// passed since the fault, send REBOOT (Dynamixel hardware errors latch until a reboot),
    /// at most `max_reboots` times in the loop's life, then resume.
    Automatic {
        /// Time in the safe state before a reboot, µs.
        cooldown_us: u64,
        /// Reboots allowed before the loop stays halted.
        max_reboots: u32,
    },
}

/// Everything a [`GraspLoop`](super::GraspLoop) needs besides its four parts.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LoopConfig {
    /// Control period, µs (10 000 = 100 Hz).
    pub period_us: u64,
    /// Target contact pressure: mean rise of the pad's sensors over their tared baseline, Pa.
    pub target_pressure_pa: f32,
    /// Mean rise above which the pad counts as touched, Pa.
    pub contact_threshold_pa: f32,
    /// Cut-off of the first-order low-pass on the pressure rate, Hz (derivative filtering).
    pub rate_cutoff_hz: f32,
    /// Cycles averaged at start, untouched and uncommanded, as each sensor's zero.
    pub tare_cycles: u32,
    /// Closing goal sent with every effort, rad (position control under a torque limit, §5).
    pub goal_rad: f32,
    /// The actuator's allowed goal range, rad; a goal outside is refused before sending.
    pub goal_limits_rad: (f32, f32),
    /// The per-object torque band every effort is clamped into.
    pub band: TorqueBand,
    /// What the actuator does on a fault, in the fault's cycle (the loop then stays safe).
    pub safe_action: SafeAction,
    /// What the hand is left doing when the loop ends
    /// ([`GraspLoop::end`](super::GraspLoop::end)).
    pub end_action: EndAction,
    /// Longest a [`EndAction::Release`] waits for the hand to open before torque off, µs.
    pub release_timeout_us: u64,
    /// How the loop leaves its safe state.
    pub recovery: Recovery,
    /// |load| under which a latched hardware error counts as cleared, fraction of maximum.
    pub clear_load_fraction: f32,
    /// Most cycle samples (and, apart, fault events) the loop keeps. When the log is full the
    /// older half is dropped (counted in
    /// [`GraspLoop::log_dropped`](super::GraspLoop::log_dropped)), so a loop that runs for
    /// days holds bounded memory and the newest `log_capacity / 2` cycles at least.
    pub log_capacity: usize,
}

impl LoopConfig {
    /// The default control period, µs: 100 Hz, the rate the fingertips are read at.
    pub const DEFAULT_PERIOD_US: u64 = 10_000;

    /// 100 Hz, 500 Pa target (about the mean rise of the grasping paper's fingertip under a 5 N
    /// whole-pad grip), 50 Pa contact threshold, 2 Hz rate filter, 10 tare cycles,
    /// goal 0.2 rad within 0…0.5 rad, the full band, hold last safe effort on a fault, manual
    /// recovery, release at the end (at most 3 s to open: an MX-28 at a third of its PWM opens
    /// π rad in about 1.6 s), a log of 65 536 cycles (10.9 min at 100 Hz, ≈ 6 MB for a
    /// 3-sensor pad).
    pub fn new() -> LoopConfig {
        LoopConfig {
            period_us: Self::DEFAULT_PERIOD_US,
            target_pressure_pa: 500.0,
            contact_threshold_pa: 50.0,
            rate_cutoff_hz: 2.0,
            tare_cycles: 10,
            goal_rad: 0.2,
            goal_limits_rad: (0.0, 0.5),
            band: TorqueBand::FULL,
            safe_action: SafeAction::HoldLastSafeEffort,
            end_action: EndAction::Release,
            release_timeout_us: 3_000_000,
            recovery: Recovery::Manual,
            clear_load_fraction: 0.05,
            log_capacity: 65_536,
        }
    }

    /// Checks every value; the loop refuses to start on an error.
    ///
    /// ```
    /// # use hand_control::grasp_loop::LoopConfig;
    /// assert!(LoopConfig::new().validate().is_ok());
    /// let bad = LoopConfig { period_us: 0, ..LoopConfig::new() };
    /// assert!(bad.validate().is_err());
    /// assert!(LoopConfig { log_capacity: 1, ..LoopConfig::new() }.validate().is_err());
    /// ```
    pub fn validate(&self) -> Result<(), ConfigError> {
        let positive = |name: &'static str, v: f32| {
            if v.is_finite() && v > 0.0 {
                Ok(())
            } else {
                Err(ConfigError::NotPositive { name, value: v })
            }
        };
        if self.period_us == 0 {
            return Err(ConfigError::NotPositive {
                name: "period_us",
                value: 0.0,
            });
        }
        positive("target_pressure_pa", self.target_pressure_pa)?;
        positive("contact_threshold_pa", self.contact_threshold_pa)?;
        positive("rate_cutoff_hz", self.rate_cutoff_hz)?;
        if self.tare_cycles == 0 {
            return Err(ConfigError::NotPositive {
                name: "tare_cycles",
                value: 0.0,
            });
        }
        if !(0.0..=1.0).contains(&self.clear_load_fraction) {
            return Err(ConfigError::NotPositive {
                name: "clear_load_fraction",
                value: self.clear_load_fraction,
            });
        }
        let (lo, hi) = self.goal_limits_rad;
        if !(lo.is_finite() && hi.is_finite() && lo <= hi) {
            return Err(ConfigError::GoalLimits { lo, hi });
        }
        check_goal(self.goal_rad, self.goal_limits_rad)?;
        if self.log_capacity < 2 {
            return Err(ConfigError::NotPositive {
                name: "log_capacity (at least 2)",
                value: self.log_capacity as f32,
            });
        }
        Ok(())
    }
}

impl Default for LoopConfig {
    fn default() -> Self {
        LoopConfig::new()
    }
}

/// `goal_rad` if it is finite and inside `limits`.
pub(crate) fn check_goal(goal_rad: f32, limits: (f32, f32)) -> Result<f32, ConfigError> {
    if goal_rad.is_finite() && (limits.0..=limits.1).contains(&goal_rad) {
        Ok(goal_rad)
    } else {
        Err(ConfigError::GoalOutOfRange {
            goal_rad,
            lo: limits.0,
            hi: limits.1,
        })
    }
}

/// A configuration or command the loop refuses before anything is sent.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ConfigError {
    /// A value that must be positive and finite is not.
    #[error("{name} must be positive and finite, got {value}")]
    NotPositive {
        /// The field.
        name: &'static str,
        /// Its value.
        value: f32,
    },
    /// The torque band is empty or leaves 0…1023.
    #[error("torque band {min_raw}…{max_raw} is not inside 0…1023 in order")]
    TorqueBand {
        /// The band's low end.
        min_raw: u16,
        /// The band's high end.
        max_raw: u16,
    },
    /// The goal limits are not finite or not in order.
    #[error("goal limits {lo}…{hi} rad are not finite and in order")]
    GoalLimits {
        /// Low limit, rad.
        lo: f32,
        /// High limit, rad.
        hi: f32,
    },
    /// A goal outside the actuator's allowed range (an out-of-range command).
    #[error("goal {goal_rad} rad is outside {lo}…{hi} rad")]
    GoalOutOfRange {
        /// The refused goal, rad.
        goal_rad: f32,
        /// Low limit, rad.
        lo: f32,
        /// High limit, rad.
        hi: f32,
    },
}
