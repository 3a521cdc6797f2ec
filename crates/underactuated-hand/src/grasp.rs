//! One grasp as the underactuated-hand softness paper records it (§3.1): the actuator closes at
//! constant velocity, open loop; the series starts at first contact t₁ ("when any finger of
//! the robotic hand is in contact with the surface of the object") and ends at t₂ = 14 s, when
//! the actuator's motion has reached its steady state. [`Recorder`] turns timed samples into
//! that series, whatever reads them (a board, a log, a simulator).

/// How a grasp is closed and recorded.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GraspPlan {
    /// The tendon's closing speed, mm/s: constant, open loop.
    pub closing_speed_mm_s: f64,
    /// The window from first contact, s (the paper's 14).
    pub window_s: f64,
    /// Samples per second in the window (the rate the classifier's training series have).
    pub sample_hz: f64,
    /// The longest approach before first contact, s: a grasp that has touched nothing by then
    /// is empty.
    pub approach_timeout_s: f64,
    /// The force any finger must read for contact, N (at least the FSR's rated floor).
    pub contact_n: f64,
}

impl Default for GraspPlan {
    /// 1.5 mm/s, 14 s at 10 Hz, 60 s of approach, contact at 0.1 N (the SF10-60's 10 g floor).
    fn default() -> GraspPlan {
        GraspPlan {
            closing_speed_mm_s: 1.5,
            window_s: 14.0,
            sample_hz: 10.0,
            approach_timeout_s: 60.0,
            contact_n: 0.1,
        }
    }
}

impl GraspPlan {
    /// Samples in a full window: both ends included (`14 s × 10 Hz + 1` = 141).
    pub fn samples(&self) -> usize {
        (self.window_s * self.sample_hz).round() as usize + 1
    }

    fn period_us(&self) -> u64 {
        (1e6 / self.sample_hz).round() as u64
    }

    /// What is wrong with the plan, if anything.
    pub fn check(&self) -> Result<(), &'static str> {
        let within = |x: f64, lo: f64, hi: f64| x.is_finite() && x > lo && x <= hi;
        if !within(self.closing_speed_mm_s, 0.0, 100.0) {
            return Err("closing_speed_mm_s must be in (0, 100] mm/s");
        }
        if !within(self.window_s, 0.0, 600.0) {
            return Err("window_s must be in (0, 600] s");
        }
        if !within(self.sample_hz, 0.0, 1000.0) {
            return Err("sample_hz must be in (0, 1000] Hz");
        }
        if !within(self.approach_timeout_s, 0.0, 3600.0) {
            return Err("approach_timeout_s must be in (0, 3600] s");
        }
        if !(self.contact_n.is_finite() && self.contact_n >= 0.0) {
            return Err("contact_n must be finite and not negative");
        }
        Ok(())
    }
}

/// Where a recording stands after a sample.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Phase {
    /// No finger has touched yet.
    Approaching,
    /// Recording the window: this many samples so far.
    Recording(usize),
    /// The window is full.
    Done,
    /// Nothing was touched within the approach timeout: an empty grasp.
    Empty,
}

/// Builds a grasp's series from samples as they come: `[f1_n…f4_n, a1_deg…a4_deg]` at
/// `sample_hz` from first contact. Each grid time `t₁ + k / sample_hz` takes the first sample
/// read at or after it; a reading source faster than the grid (a board reporting every 19 ms)
/// so gives the series the paper's rate.
///
/// ```
/// use underactuated_hand::grasp::{GraspPlan, Phase, Recorder};
/// let plan = GraspPlan { window_s: 1.0, ..GraspPlan::default() };
/// let mut rec = Recorder::new(plan, 0);
/// let mut phase = Phase::Approaching;
/// for k in 0..100u64 {
///     // 20 ms samples; the fingers touch at 0.5 s.
///     let force = if k >= 25 { 2.0 } else { 0.0 };
///     phase = rec.push(k * 20_000, [force, 0.0, 0.0, 0.0, 10.0, 10.0, 10.0, 10.0]);
///     if phase == Phase::Done {
///         break;
///     }
/// }
/// assert_eq!(phase, Phase::Done);
/// assert_eq!(rec.first_contact_us(), Some(500_000));
/// assert_eq!(rec.series().len(), 11 * 8); // 1 s at 10 Hz, both ends
/// ```
#[derive(Debug, Clone)]
pub struct Recorder {
    plan: GraspPlan,
    start_us: u64,
    first_contact_us: Option<u64>,
    series: Vec<f32>,
    phase: Phase,
}

impl Recorder {
    /// A recording of `plan` whose close started at `start_us` (the samples' clock).
    pub fn new(plan: GraspPlan, start_us: u64) -> Recorder {
        Recorder {
            plan,
            start_us,
            first_contact_us: None,
            series: Vec::with_capacity(plan.samples() * 8),
            phase: Phase::Approaching,
        }
    }

    /// Takes the sample read at `t_us`.
    pub fn push(&mut self, t_us: u64, sample: [f32; 8]) -> Phase {
        match self.phase {
            Phase::Done | Phase::Empty => return self.phase,
            Phase::Approaching => {
                let touching = sample[..4]
                    .iter()
                    .any(|f| f64::from(*f) >= self.plan.contact_n && *f > 0.0);
                if !touching {
                    let waited = t_us.saturating_sub(self.start_us) as f64 * 1e-6;
                    if waited > self.plan.approach_timeout_s {
                        self.phase = Phase::Empty;
                    }
                    return self.phase;
                }
                self.first_contact_us = Some(t_us);
            }
            Phase::Recording(_) => {}
        }
        let t1 = self.first_contact_us.unwrap_or(t_us);
        let mut taken = self.series.len() / 8;
        // Every grid time this reading is the first at or after (several, from a slow source).
        while taken < self.plan.samples() && t_us >= t1 + taken as u64 * self.plan.period_us() {
            self.series.extend_from_slice(&sample);
            taken += 1;
        }
        self.phase = if taken >= self.plan.samples() {
            Phase::Done
        } else {
            Phase::Recording(taken)
        };
        self.phase
    }

    /// Where it stands.
    pub fn phase(&self) -> Phase {
        self.phase
    }

    /// When the first finger touched, in the samples' clock.
    pub fn first_contact_us(&self) -> Option<u64> {
        self.first_contact_us
    }

    /// The series so far, flat: eight readings per sample.
    pub fn series(&self) -> &[f32] {
        &self.series
    }

    /// The plan it records.
    pub fn plan(&self) -> &GraspPlan {
        &self.plan
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_empty_grasp_ends_at_the_approach_timeout() {
        let plan = GraspPlan {
            approach_timeout_s: 0.5,
            ..GraspPlan::default()
        };
        let mut rec = Recorder::new(plan, 1_000_000);
        assert_eq!(rec.push(1_400_000, [0.0; 8]), Phase::Approaching);
        assert_eq!(rec.push(1_500_001, [0.0; 8]), Phase::Empty);
        // Contact after it ends changes nothing.
        assert_eq!(rec.push(1_600_000, [5.0; 8]), Phase::Empty);
        assert!(rec.series().is_empty());
    }

    #[test]
    fn a_slow_source_fills_every_grid_time_it_is_the_first_reading_after() {
        let plan = GraspPlan {
            window_s: 1.0,
            ..GraspPlan::default()
        };
        let mut rec = Recorder::new(plan, 0);
        // 250 ms readings, in contact from the first, each one's time (s) + 1 as its value:
        // the window is full at 1 s.
        let mut t = 0;
        while rec.push(t, [1.0 + t as f32 * 1e-6; 8]) != Phase::Done {
            t += 250_000;
            assert!(t < 10_000_000, "never done");
        }
        assert_eq!(t, 1_000_000);
        let firsts: Vec<f32> = rec.series().chunks(8).map(|s| s[0]).collect();
        assert_eq!(
            firsts,
            [1.0, 1.25, 1.25, 1.5, 1.5, 1.5, 1.75, 1.75, 2.0, 2.0, 2.0]
        );
    }

    #[test]
    fn a_bad_plan_is_refused_in_words() {
        let bad = GraspPlan {
            sample_hz: 0.0,
            ..GraspPlan::default()
        };
        assert!(bad.check().unwrap_err().contains("sample_hz"));
        assert_eq!(GraspPlan::default().samples(), 141);
    }
}
