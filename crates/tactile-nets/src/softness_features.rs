//! Our variant of the softness classifier's inputs (`docs/learning.md` §2): the paper's
//! 8 → 4 → 4 → 3 network and Levenberg–Marquardt training unchanged, fed readings that do not
//! depend on *which* finger met which side of the object.
//!
//! Why: the irregular household objects give each finger its own local stiffness, and the
//! object's class is its overall one; a network that reads finger 1's force as finger 1's
//! learns where the soft side happened to sit in the training grasps. Sorting the four
//! fingers' readings keeps what the fingers felt and drops who felt it.
//!
//! Two candidates, chosen between on household validation objects drawn for the choice, never
//! the test sets (`paper_experiments::softness_eval::validate_features`, in the repository):
//! - [`Features::SortedSeries`]: every sample of the series, its four forces sorted and its
//!   four angles sorted (ascending), classified by the mean output over the series like the
//!   paper's input;
//! - [`Features::FingerStiffness`]: one row per grasp, each finger's stiffness estimate — force
//!   gained over distal-angle travel, `ln((Δf + 0.05 N) / (Δa⁺ + 0.5°))` from the first sample at
//!   0.5 N to the first at 2 N, and again to 15 N (the series' last sample when a level is never
//!   reached) — the four of each level sorted.
//!
//! ```
//! use tactile_nets::softness_features::Features;
//! // Finger 1 soft, fingers 2–4 hard; then the same grasp with fingers 1 and 3 swapped.
//! let grasp = |soft: usize| -> Vec<[f32; 8]> {
//!     (0..50).map(|i| {
//!         let t = i as f32 / 10.0;
//!         let mut s = [0.0; 8];
//!         for f in 0..4 {
//!             let (force, angle) = if f == soft { (t, 10.0 * t) } else { (8.0 * t, t) };
//!             s[f] = force;
//!             s[4 + f] = angle;
//!         }
//!         s
//!     }).collect()
//! };
//! for features in Features::CANDIDATES {
//!     assert_eq!(features.rows(&grasp(0)), features.rows(&grasp(2)));
//! }
//! assert_eq!(Features::FingerStiffness.rows(&grasp(0)).len(), 1);
//! ```

use crate::softness::N_VARIABLES;

/// Training rows of a series: every 14th sample (1.4 s apart at 10 Hz, 11 per grasp), the
/// paper's training rows; inference reads every sample.
pub const SERIES_STRIDE: usize = 14;

/// Fingers per grasp (forces first, then angles, in each sample).
const FINGERS: usize = N_VARIABLES / 2;
/// Force at which a finger counts as in contact for the stiffness estimate, N.
const CONTACT_N: f32 = 0.5;
/// The two force levels the stiffness is measured up to, N.
const LEVELS_N: [f32; 2] = [2.0, 15.0];
/// Floors keeping the estimate finite for a finger that never moved or never pushed.
const FORCE_FLOOR_N: f32 = 0.05;
const ANGLE_FLOOR_DEG: f32 = 0.5;

/// Which finger-order-invariant inputs the network reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Features {
    /// The paper's inputs, as they are (the baseline the candidates are validated against).
    Paper,
    /// Every sample, forces sorted and angles sorted.
    SortedSeries,
    /// One row: sorted per-finger stiffness up to 2 N and up to 15 N.
    FingerStiffness,
}

impl Features {
    /// The paper's inputs and both candidates.
    pub const ALL: [Features; 3] = [
        Features::Paper,
        Features::SortedSeries,
        Features::FingerStiffness,
    ];
    /// Our candidates (finger-order invariant).
    pub const CANDIDATES: [Features; 2] = [Features::SortedSeries, Features::FingerStiffness];

    /// File and metrics name.
    pub fn name(self) -> &'static str {
        match self {
            Features::Paper => "paper",
            Features::SortedSeries => "sorted_series",
            Features::FingerStiffness => "finger_stiffness",
        }
    }

    /// The candidate named `name`.
    pub fn from_name(name: &str) -> Option<Features> {
        Features::ALL.into_iter().find(|f| f.name() == name)
    }

    /// Training stride over [`Features::rows`]: the paper's every 14th sample for a series,
    /// every row for the one-row form.
    pub fn stride(self) -> usize {
        match self {
            Features::Paper | Features::SortedSeries => SERIES_STRIDE,
            Features::FingerStiffness => 1,
        }
    }

    /// The rows the network reads for one grasp's series (finite for finite readings; an
    /// empty series gives no rows).
    pub fn rows(self, series: &[[f32; N_VARIABLES]]) -> Vec<[f32; N_VARIABLES]> {
        match self {
            Features::Paper => series.to_vec(),
            Features::SortedSeries => series.iter().map(sorted_sample).collect(),
            Features::FingerStiffness if series.is_empty() => Vec::new(),
            Features::FingerStiffness => {
                let mut out = [0.0; N_VARIABLES];
                for (l, level) in LEVELS_N.iter().enumerate() {
                    let mut k: [f32; FINGERS] =
                        core::array::from_fn(|f| stiffness(series, f, *level));
                    k.sort_by(f32::total_cmp);
                    out[l * FINGERS..(l + 1) * FINGERS].copy_from_slice(&k);
                }
                vec![out]
            }
        }
    }
}

fn sorted_sample(s: &[f32; N_VARIABLES]) -> [f32; N_VARIABLES] {
    let mut out = *s;
    out[..FINGERS].sort_by(f32::total_cmp);
    out[FINGERS..].sort_by(f32::total_cmp);
    out
}

/// `ln((Δf + floor) / (Δa⁺ + floor))` of finger `f` from the first sample at [`CONTACT_N`] to
/// the first at `level` (or the last sample).
fn stiffness(series: &[[f32; N_VARIABLES]], f: usize, level: f32) -> f32 {
    let last = series.len().saturating_sub(1);
    let first_at = |x: f32| series.iter().position(|s| s[f] >= x).unwrap_or(last);
    let i0 = first_at(CONTACT_N);
    let i1 = first_at(level).max((i0 + 1).min(last));
    let df = (series[i1][f] - series[i0][f]).max(0.0);
    let da = (series[i1][FINGERS + f] - series[i0][FINGERS + f]).max(0.0);
    ((df + FORCE_FLOOR_N) / (da + ANGLE_FLOOR_DEG)).ln()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stiffness_orders_a_hard_finger_above_a_soft_one_and_stays_finite() {
        // Hard: 8 N per degree; soft: 0.1 N per degree; silent: never touches.
        let series: Vec<[f32; N_VARIABLES]> = (0..60)
            .map(|i| {
                let a = i as f32;
                [8.0 * a, 0.1 * a, 0.0, 0.0, a, a, a, 0.0]
            })
            .collect();
        let k: Vec<f32> = (0..FINGERS).map(|f| stiffness(&series, f, 15.0)).collect();
        assert!(k[0] > k[1], "{k:?}");
        assert!(k.iter().all(|v| v.is_finite()), "{k:?}");
        assert_eq!(Features::FingerStiffness.rows(&[]), Vec::<[f32; 8]>::new());
    }
}
