//! One recorded grasp: the series of seed 001 §3.1, from first contact t₁ to t₂, 14 s later.

use super::{Underactuated, UnderactuatedConfig};
use crate::SimError;
use crate::scene::Model;
use hand_traits::{FingerFrame, TactileSource};

/// A grasp's sensor series.
#[derive(Debug, Clone, PartialEq)]
pub struct GraspSeries {
    /// First contact t₁, s since the actuator started; `None` for an empty grasp, whose series
    /// then starts at 0.
    pub first_contact_s: Option<f64>,
    /// Frames at `t₁ + k / sample_hz` up to the grasp's end (`duration_s` after t₁), time
    /// stamps since the actuator started.
    pub frames: Vec<FingerFrame<4>>,
}

/// Runs one grasp of `config` with `seed` and samples it at `sample_hz` from first contact t₁
/// to `config.duration_s` later (from 0 for an empty grasp).
///
/// ```
/// use hand_sim::underactuated::{record_grasp, UnderactuatedConfig};
/// let series = record_grasp(&UnderactuatedConfig::default(), 1, 10.0)?;
/// let t1 = series.first_contact_s.expect("an 80 mm cylinder is touched");
/// assert!(t1 > 0.0);
/// assert_eq!(series.frames.len(), 141);
/// # Ok::<(), hand_sim::SimError>(())
/// ```
pub fn record_grasp(
    config: &UnderactuatedConfig,
    seed: u64,
    sample_hz: f64,
) -> Result<GraspSeries, SimError> {
    if !sample_hz.is_finite() || sample_hz <= 0.0 || sample_hz > 1e4 {
        let why = format!("must be in (0, 10000] Hz, got {sample_hz}");
        return Err(SimError::config("sample_hz", why));
    }
    let mut hand = Underactuated::new(config, seed)?;
    let step = hand.step_ns();
    while hand.first_contact_ns().is_none() && hand.steps() * step < hand.end_ns() {
        hand.step_to((hand.steps() + 1) * step)?;
    }
    let t1 = hand.first_contact_ns();
    let start = t1.unwrap_or(0);
    let period = (1e9 / sample_hz).round() as u64;
    let samples = hand.end_ns().saturating_sub(start) / period;
    let mut frames = Vec::with_capacity(samples as usize + 1);
    for k in 0..=samples {
        hand.step_to(start + k * period)?;
        frames.push(hand.read_frame()?);
    }
    Ok(GraspSeries {
        first_contact_s: t1.map(|t| t as f64 * 1e-9),
        frames,
    })
}
