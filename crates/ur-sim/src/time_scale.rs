//! How fast the simulated controller's time runs against the wall clock.

use std::time::Duration;

/// Simulated seconds per wall-clock second: 1 is real time, 4 runs every move four times faster.
///
/// The control cycle stays 8 ms of controller time (the RTDE `timestamp`, the motion profiles
/// and the safety checks see the same steps); only the wall-clock wait between cycles, and
/// between RTDE data packages, shrinks. ur_rtde's own timeouts are wall-clock, so a scale below
/// 1 stretches every move against them.
///
/// ```
/// use ur_sim::TimeScale;
/// let fast: TimeScale = "4".parse()?;
/// assert_eq!(fast.wall(std::time::Duration::from_millis(8)).as_micros(), 2_000);
/// assert!("0".parse::<TimeScale>().is_err());
/// assert!("fast".parse::<TimeScale>().is_err());
/// # Ok::<(), ur_sim::TimeScaleError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TimeScale(f64);

impl TimeScale {
    /// Real time.
    pub const REAL_TIME: TimeScale = TimeScale(1.0);

    /// A scale of `factor`; it must be finite and positive.
    pub fn new(factor: f64) -> Result<TimeScale, TimeScaleError> {
        if factor.is_finite() && factor > 0.0 {
            Ok(TimeScale(factor))
        } else {
            Err(TimeScaleError::NotPositive(factor.to_string()))
        }
    }

    /// Simulated seconds per wall-clock second.
    pub fn factor(self) -> f64 {
        self.0
    }

    /// The wall-clock time that `simulated` takes.
    pub fn wall(self, simulated: Duration) -> Duration {
        simulated.div_f64(self.0)
    }
}

impl Default for TimeScale {
    fn default() -> Self {
        TimeScale::REAL_TIME
    }
}

impl core::str::FromStr for TimeScale {
    type Err = TimeScaleError;

    fn from_str(s: &str) -> Result<TimeScale, TimeScaleError> {
        let factor: f64 = s
            .trim()
            .parse()
            .map_err(|_| TimeScaleError::NotANumber(s.to_owned()))?;
        TimeScale::new(factor)
    }
}

/// A time scale that is not a finite positive number.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum TimeScaleError {
    /// The text is not a number.
    #[error("time scale {0:?} is not a number")]
    NotANumber(String),
    /// Zero, negative, infinite or NaN.
    #[error("time scale {0} must be finite and positive (1 = real time)")]
    NotPositive(String),
}
