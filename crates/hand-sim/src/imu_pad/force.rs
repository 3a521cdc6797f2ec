//! Force from contact depth (Yeoh law, fitted through the published points) and pressure
//! counts from force (the inverse of eq. 1).
//!
//! **Depth → force.** Seed 002 §III-C treats the pad as the Ecoflex 00-30 case compressed
//! under the tip and turns a stress into a force over the pad area (eq. 3, 276 mm²). We do the
//! same with the incompressible uniaxial Yeoh nominal stress (eq. 2, `C1…C3`):
//!
//! `σ(λ) = −2 (λ − λ⁻²) [C1 + 2 C2 (I1 − 3) + 3 C3 (I1 − 3)²]`, `I1 = λ² + 2/λ`,
//! `λ = 1 − d / h_eff`, and `F(d) = g · A · σ(λ)`.
//!
//! The two free numbers, an effective thickness `h_eff` (the 10 mm sphere strains less material
//! than the whole 4.5 mm case) and a gain `g`, are fitted by least squares on relative error
//! through the published points (0.8 mm 3.5 N, 1.3 mm 8 N, 1.7 mm 13 N: §III-C, Fig. 6B / 7B):
//! `g` in closed form for each `h_eff`, `h_eff` by golden-section search.
//!
//! **Force → counts.** Eq. 1, `F(p) = a2 p² + a1 p + a0`, inverted on its rising branch; forces
//! below `a0` (2.33 N) give no counts: the paper finds no response below about 3.5 N.

use crate::SimError;

/// The third-order Yeoh constants `C1…C3` of eq. 2, in kPa (seed 002 §III-C, Ecoflex 00-30).
///
/// The volumetric `D_i` are not used: the uniaxial law here is the incompressible one.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Yeoh {
    /// `C1`, kPa.
    pub c1_kpa: f64,
    /// `C2`, kPa.
    pub c2_kpa: f64,
    /// `C3`, kPa.
    pub c3_kpa: f64,
}

impl Yeoh {
    /// Compressive nominal stress (positive in compression), kPa, at stretch `lambda` in (0, 1].
    pub fn compressive_stress_kpa(&self, lambda: f64) -> f64 {
        let i1 = lambda * lambda + 2.0 / lambda - 3.0;
        let slope = self.c1_kpa + 2.0 * self.c2_kpa * i1 + 3.0 * self.c3_kpa * i1 * i1;
        -2.0 * (lambda - 1.0 / (lambda * lambda)) * slope
    }
}

/// Largest compressive strain the law is evaluated at: the pad is solid beyond (and the paper
/// reports the output saturating at 1.7 mm); deeper contacts read as this strain.
const MAX_STRAIN: f64 = 0.9;

/// The fitted depth → force curve at the chip (contact position 13, centre column).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ForceDepthCurve {
    yeoh: Yeoh,
    area_mm2: f64,
    /// Effective compressed thickness, mm.
    pub h_eff_mm: f64,
    /// Gain on `A · σ` (dimensionless).
    pub gain: f64,
}

impl ForceDepthCurve {
    /// Fits `h_eff` and the gain through `points` (depth mm, force N).
    ///
    /// ```
    /// use hand_sim::imu_pad::force::{ForceDepthCurve, Yeoh};
    /// let yeoh = Yeoh { c1_kpa: 17.0, c2_kpa: -0.2, c3_kpa: 0.023 };
    /// let curve = ForceDepthCurve::fit(yeoh, 276.0, &[[0.8, 3.5], [1.3, 8.0], [1.7, 13.0]])?;
    /// assert!((curve.force_n(1.3) - 8.0).abs() < 0.5);
    /// # Ok::<(), hand_sim::SimError>(())
    /// ```
    pub fn fit(yeoh: Yeoh, area_mm2: f64, points: &[[f64; 2]]) -> Result<Self, SimError> {
        let field = "mechanics.force_points";
        if points.is_empty() {
            return Err(SimError::config(field, "at least one (depth, force) point"));
        }
        if points
            .iter()
            .any(|[d, f]| !(d.is_finite() && f.is_finite() && *d > 0.0 && *f > 0.0))
        {
            return Err(SimError::config(field, "depths and forces finite and > 0"));
        }
        if !(area_mm2.is_finite() && area_mm2 > 0.0) {
            return Err(SimError::config("mechanics.area_mm2", "finite and > 0"));
        }
        let d_max = points.iter().map(|p| p[0]).fold(0.0, f64::max);
        let shape = |h: f64, d: f64| area_mm2 * 1e-3 * yeoh.compressive_stress_kpa(1.0 - d / h);
        // For a given h, the relative-error least-squares gain, and its cost.
        let solve = |h: f64| {
            let (num, den) = points.iter().fold((0.0, 0.0), |(n, m), [d, f]| {
                let r = shape(h, *d) / f;
                (n + r, m + r * r)
            });
            let gain = num / den;
            let cost: f64 = points
                .iter()
                .map(|[d, f]| ((gain * shape(h, *d) - f) / f).powi(2))
                .sum();
            (gain, cost)
        };
        // Golden-section search on h between "the deepest point is at MAX_STRAIN" and 20×.
        let (mut lo, mut hi) = (d_max / MAX_STRAIN, 20.0 * d_max / MAX_STRAIN);
        let phi = 0.5 * (5.0_f64.sqrt() - 1.0);
        for _ in 0..100 {
            let a = hi - phi * (hi - lo);
            let b = lo + phi * (hi - lo);
            if solve(a).1 < solve(b).1 {
                hi = b;
            } else {
                lo = a;
            }
        }
        let h_eff_mm = 0.5 * (lo + hi);
        let (gain, _) = solve(h_eff_mm);
        if !(gain.is_finite() && gain > 0.0) {
            return Err(SimError::config(
                field,
                "no positive Yeoh fit through these points",
            ));
        }
        Ok(ForceDepthCurve {
            yeoh,
            area_mm2,
            h_eff_mm,
            gain,
        })
    }

    /// Force, N, at contact depth `depth_mm`: 0 for no contact (≤ 0 or NaN), saturating at
    /// the largest strain the law is evaluated at.
    pub fn force_n(&self, depth_mm: f64) -> f64 {
        // NaN and no contact alike: no force.
        if depth_mm.is_nan() || depth_mm <= 0.0 {
            return 0.0;
        }
        let strain = (depth_mm / self.h_eff_mm).min(MAX_STRAIN);
        self.gain * self.area_mm2 * 1e-3 * self.yeoh.compressive_stress_kpa(1.0 - strain)
    }
}

/// Eq. 1, `F(p) = a2 p² + a1 p + a0` (N, `p` in counts), and its inverse.
#[derive(Debug, Clone, Copy, PartialEq, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ForceCounts {
    /// `a2`, N/count².
    pub a2: f64,
    /// `a1`, N/count.
    pub a1: f64,
    /// `a0`, N.
    pub a0: f64,
}

impl Default for ForceCounts {
    /// Seed 002 eq. 1: 5.844e-6, 0.0041, 2.3304.
    fn default() -> Self {
        ForceCounts {
            a2: 5.844e-6,
            a1: 0.0041,
            a0: 2.3304,
        }
    }
}

impl ForceCounts {
    /// Checks that the polynomial is rising for `p ≥ 0` (so it has an inverse there).
    pub fn validate(&self) -> Result<(), SimError> {
        let ok = [self.a2, self.a1, self.a0].iter().all(|c| c.is_finite())
            && self.a2 >= 0.0
            && self.a1 > 0.0;
        if ok {
            Ok(())
        } else {
            Err(SimError::config(
                "pressure.eq1",
                "finite, a2 ≥ 0 and a1 > 0",
            ))
        }
    }

    /// `F(p)`, N.
    pub fn force_n(&self, counts: f64) -> f64 {
        (self.a2 * counts + self.a1) * counts + self.a0
    }

    /// The counts `p ≥ 0` with `F(p) = force_n`; 0 when `force_n ≤ a0` (or NaN).
    ///
    /// ```
    /// use hand_sim::imu_pad::force::ForceCounts;
    /// let eq1 = ForceCounts::default();
    /// let p = eq1.counts(8.0);
    /// assert!((eq1.force_n(p) - 8.0).abs() < 1e-9);
    /// assert_eq!(eq1.counts(1.0), 0.0);
    /// ```
    pub fn counts(&self, force_n: f64) -> f64 {
        let excess = force_n - self.a0;
        if excess.is_nan() || excess <= 0.0 {
            return 0.0;
        }
        let p = if self.a2 > 0.0 {
            // The cancellation-free root: 2c / (b + √(b² + 4ac)).
            2.0 * excess / (self.a1 + (self.a1 * self.a1 + 4.0 * self.a2 * excess).sqrt())
        } else {
            excess / self.a1
        };
        if p.is_finite() { p } else { f64::MAX }
    }
}
