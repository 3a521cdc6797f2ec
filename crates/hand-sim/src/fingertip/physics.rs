//! The fingertip's true pressures over time: baseline, drift, re-zero, and the delayed
//! first-order response to a timeline of contacts.

use super::contact::{ContactPatch, offset_in_range};
use super::geometry::SENSORS;
use super::law::LawParams;
use crate::SimError;
use std::collections::VecDeque;

/// One change of the contact at `t_ns`: each sensor's steady rise moves by `delta_hpa`, seen by
/// sensor `k` after `delay_ns[k]`.
#[derive(Debug, Clone, Copy)]
struct Step {
    t_ns: u64,
    delta_hpa: [f64; SENSORS],
    delay_ns: [u64; SENSORS],
}

/// A step this many time constants old has completed to within e^-20 ≈ 2e-9 of its size, so it
/// is folded into the settled sum: long closed-loop runs stay O(1) per evaluation.
const SETTLED_TIME_CONSTANTS: f64 = 20.0;

/// The pad's true pressures: what the three chip models are asked to measure.
#[derive(Debug, Clone)]
pub struct FingertipPhysics {
    law: LawParams,
    baseline_hpa: [f64; SENSORS],
    drift_hpa_per_s: f64,
    drift_since_ns: u64,
    current: ContactPatch,
    last_change_ns: u64,
    settled_hpa: [f64; SENSORS],
    recent: VecDeque<Step>,
}

impl FingertipPhysics {
    /// A pad at rest with per-sensor `baseline_hpa` that drifts by `drift_hpa_per_min`.
    pub fn new(
        law: LawParams,
        baseline_hpa: [f64; SENSORS],
        drift_hpa_per_min: f64,
    ) -> Result<Self, SimError> {
        if baseline_hpa.iter().any(|b| !(10.0..=1200.0).contains(b)) {
            return Err(SimError::config(
                "baseline_hpa",
                "each within the MS5611's 10…1200 mbar",
            ));
        }
        if !drift_hpa_per_min.is_finite() || drift_hpa_per_min.abs() > 10.0 {
            return Err(SimError::config(
                "drift_hpa_per_min",
                "finite, at most 10 hPa/min",
            ));
        }
        Ok(Self {
            law,
            baseline_hpa,
            drift_hpa_per_s: drift_hpa_per_min / 60.0,
            drift_since_ns: 0,
            current: ContactPatch::NONE,
            last_change_ns: 0,
            settled_hpa: [0.0; SENSORS],
            recent: VecDeque::new(),
        })
    }

    /// The law in use.
    pub fn law(&self) -> &LawParams {
        &self.law
    }

    /// The contact in force since the last [`set_contact`](Self::set_contact).
    pub fn contact(&self) -> ContactPatch {
        self.current
    }

    /// From `t_ns` on, the pad is pressed by `patch` (or released, with [`ContactPatch::NONE`]).
    ///
    /// Times must not go backwards. A force that is negative or NaN is rejected, as is a
    /// shift beyond half a cell or NaN; forces beyond the law's clamp saturate.
    pub fn set_contact(&mut self, t_ns: u64, patch: ContactPatch) -> Result<(), SimError> {
        if t_ns < self.last_change_ns {
            return Err(SimError::config(
                "contact time",
                "contacts must be given in time order",
            ));
        }
        if patch.force_n.is_nan() || patch.force_n < 0.0 {
            return Err(SimError::config("force", "a force is zero or positive"));
        }
        if !offset_in_range(patch.offset_mm) {
            return Err(SimError::config(
                "offset_mm",
                "a patch shifts at most half a cell (1.5 mm) each way",
            ));
        }
        let before = self.law.steady_rise_hpa(&self.current);
        let after = self.law.steady_rise_hpa(&patch);
        // A release travels the same paths as the press that it ends.
        let source = if patch.cells.is_empty() {
            self.current
        } else {
            patch
        };
        let delay_ns =
            core::array::from_fn(|k| (self.law.arrival_delay_ms(&source, k) * 1e6) as u64);
        let delta_hpa = core::array::from_fn(|k| after[k] - before[k]);
        if delta_hpa.iter().any(|d| *d != 0.0) {
            self.recent.push_back(Step {
                t_ns,
                delta_hpa,
                delay_ns,
            });
        }
        self.current = patch;
        self.last_change_ns = t_ns;
        Ok(())
    }

    /// The operator re-zeroes the bias at `t_ns` (seed 000 §4: a ~2 min pause, then 1010.xx
    /// again): the drift accumulated so far is removed.
    pub fn rezero(&mut self, t_ns: u64) {
        self.drift_since_ns = t_ns;
    }

    /// True pressure at sensor `k` (0…2 for sensors 1…3) at `t_ns`, hPa.
    ///
    /// Evaluation times may come in any order, but steps older than 20 time constants before
    /// the latest time asked are folded away, so asking far back after that is approximate.
    pub fn pressure_hpa(&mut self, k: usize, t_ns: u64) -> f64 {
        let tau_ns = self.law.time_constant_ms * 1e6;
        let horizon = (SETTLED_TIME_CONSTANTS * tau_ns) as u64;
        while let Some(step) = self.recent.front() {
            let done =
                (0..SENSORS).all(|j| t_ns.saturating_sub(step.t_ns + step.delay_ns[j]) > horizon);
            if !done {
                break;
            }
            for j in 0..SENSORS {
                self.settled_hpa[j] += step.delta_hpa[j];
            }
            self.recent.pop_front();
        }
        let k = k.min(SENSORS - 1);
        let transient: f64 = self
            .recent
            .iter()
            .map(|s| {
                let since = t_ns.saturating_sub(s.t_ns + s.delay_ns[k]) as f64;
                if t_ns < s.t_ns + s.delay_ns[k] {
                    0.0
                } else {
                    s.delta_hpa[k] * (1.0 - (-since / tau_ns).exp())
                }
            })
            .sum();
        let drift = self.drift_hpa_per_s * t_ns.saturating_sub(self.drift_since_ns) as f64 * 1e-9;
        self.baseline_hpa[k] + drift + self.settled_hpa[k] + transient
    }
}
