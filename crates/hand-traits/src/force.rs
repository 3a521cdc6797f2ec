//! Force estimation from tactile readings.

/// One gram-force in newton (standard gravity, 9.806 65 m/s²).
pub const GRAM_FORCE_N: f32 = 9.806_65e-3;

/// A normal-force estimate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ForceEstimate {
    /// The estimated normal force, in newton.
    pub force_n: f32,
    /// Whether the estimate lies within the range the estimator is valid for (a learned
    /// model's training range). `false`: an extrapolation — for a network, typically its
    /// saturated output, far from the true force — to be reported, not used as a measurement.
    pub in_range: bool,
}

impl ForceEstimate {
    /// An estimate given in gram-force, the unit of the barometric fingertip's weight table.
    ///
    /// ```
    /// # use hand_traits::ForceEstimate;
    /// let f = ForceEstimate::from_gram_force(100.0);
    /// assert!((f.force_n - 0.980_665).abs() < 1e-6);
    /// assert!((f.gram_force() - 100.0).abs() < 1e-4);
    /// ```
    pub fn from_gram_force(gf: f32) -> Self {
        Self {
            force_n: gf * GRAM_FORCE_N,
            in_range: true,
        }
    }

    /// The estimate, [`in_range`](Self::in_range) only if its gram-force lies within
    /// `[lo, hi]`.
    ///
    /// ```
    /// # use hand_traits::ForceEstimate;
    /// assert!(ForceEstimate::from_gram_force(150.0).within_gf([0.0, 200.0]).in_range);
    /// assert!(!ForceEstimate::from_gram_force(213.0).within_gf([0.0, 200.0]).in_range);
    /// ```
    pub fn within_gf(self, [lo, hi]: [f32; 2]) -> Self {
        Self {
            in_range: self.in_range && (lo..=hi).contains(&self.gram_force()),
            ..self
        }
    }

    /// The estimate in gram-force.
    pub fn gram_force(&self) -> f32 {
        self.force_n / GRAM_FORCE_N
    }
}

/// Estimates the contact force from a tactile input (for example three fingertip pressures).
///
/// ```
/// use hand_traits::{ForceEstimate, ForceEstimator, PressureFrame};
///
/// /// Force proportional to the summed pressure rise over a baseline.
/// struct Linear { baseline_pa: f32, n_per_pa: f32 }
///
/// impl ForceEstimator for Linear {
///     type Input = PressureFrame<3>;
///     type Error = core::convert::Infallible;
///     fn estimate_force(&mut self, frame: &Self::Input) -> Result<ForceEstimate, Self::Error> {
///         let rise: f32 = frame.pressure_pa.iter().map(|p| p - self.baseline_pa).sum();
///         Ok(ForceEstimate { force_n: rise * self.n_per_pa, in_range: true })
///     }
/// }
///
/// let mut est = Linear { baseline_pa: 101_000.0, n_per_pa: 0.01 };
/// let f = est.estimate_force(&PressureFrame { t_us: 0, pressure_pa: [101_100.0; 3] })?;
/// assert!((f.force_n - 3.0).abs() < 1e-3);
/// # Ok::<(), core::convert::Infallible>(())
/// ```
pub trait ForceEstimator {
    /// What the estimator reads: a frame, a window of frames, a feature vector.
    type Input: ?Sized;
    /// Why an estimate could not be made (a non-finite input, a wrong shape…).
    type Error: core::fmt::Debug + core::fmt::Display;

    /// Estimates the force for one input. `&mut self` lets an estimator reuse scratch buffers.
    fn estimate_force(&mut self, input: &Self::Input) -> Result<ForceEstimate, Self::Error>;
}
