//! Defuzzifiers: how an output's aggregated fuzzy set becomes one crisp value.
//!
//! The integral and maximum defuzzifiers come in three flavours:
//! [`Resolution::Samples`] follows MATLAB's `defuzz` on `n` evenly spaced points (ends included),
//! so its numbers match MATLAB's `evalfis` at the same number of points;
//! [`Resolution::Midpoints`] follows fuzzylite, which integrates with the midpoint rule on `n`
//! cells; [`Resolution::Exact`] integrates the piecewise-linear aggregated set in closed form
//! (triangle / trapezoid terms, min or product implication, max or sum aggregation), which is
//! what both sampled methods converge to.
//!
//! # Sampling bias
//!
//! The two sampled rules weigh the ends of the universe differently. End-point samples give
//! the first and last sample a full weight where the trapezoid rule would give half, so a term
//! reaching an end of the range pulls the centroid towards that end by O(1/n) of the span:
//! a probe with an output term at the end of 0…1023 and 201 samples is 2.41 off the exact
//! centroid. Midpoints integrate with an O(1/n²) error for smooth sets (0.038 in the
//! same probe) but can miss a peak narrower than one cell. Use [`Resolution::Exact`] where the
//! terms allow it; use the sampled rule of the tool whose numbers you must reproduce.

use crate::Real;

/// How finely an integral or maximum defuzzifier looks at the aggregated set.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Resolution {
    /// `n ≥ 2` evenly spaced points over `[min, max]`, ends included (MATLAB's
    /// `DefuzzificationSamples` is 101 by default).
    Samples(usize),
    /// The midpoints `min + (k + ½)·(max − min)/n` of `n ≥ 1` equal cells (fuzzylite's
    /// `resolution`, 1000 by default in pyfuzzylite 8; its bisector takes the mean of the
    /// points whose cumulative area is nearest to half, as fuzzylite does).
    Midpoints(usize),
    /// Closed form over the piecewise-linear set; needs triangle / trapezoid output terms,
    /// min or product implication and max or unbounded-sum aggregation.
    Exact,
}

/// How an output's fuzzy set becomes one crisp value.
///
/// ```
/// use fuzzy_mamdani::{Defuzzifier, Resolution};
/// let d = Defuzzifier::Centroid(Resolution::Samples(101));
/// assert!(d.is_integral());
/// assert!(!Defuzzifier::CenterAverage.is_integral());
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Defuzzifier {
    /// Centre of gravity ∫x μ / ∫μ.
    Centroid(Resolution),
    /// The x that splits the area in halves.
    Bisector(Resolution),
    /// Mean of the points where μ is maximal (MATLAB `mom`; scikit-fuzzy `mom`).
    MeanOfMaximum(Resolution),
    /// Smallest x where μ is maximal (fuzzylite and scikit-fuzzy; MATLAB takes the smallest
    /// magnitude instead, which differs only for maxima on both sides of zero).
    SmallestOfMaximum(Resolution),
    /// Largest x where μ is maximal.
    LargestOfMaximum(Resolution),
    /// Σ wᵣ cᵣ / Σ wᵣ over the fired rules, wᵣ the rule's weighted strength and cᵣ the centre of
    /// its consequent term: Wang's center-average defuzzifier, the grasp paper's choice.
    /// Terms without a natural centre (sigmoid, S, Z) use their centroid over the universe.
    CenterAverage,
    /// Σ hₜ cₜ / Σ hₜ over the output terms, hₜ the aggregation of the strengths of the rules
    /// concluding term t: center average after aggregation.
    WeightedAverage,
}

impl Defuzzifier {
    /// Whether the defuzzifier looks at the aggregated set (true) or only at term centres.
    pub fn is_integral(&self) -> bool {
        self.resolution().is_some()
    }

    /// The resolution of an integral / maximum defuzzifier.
    pub fn resolution(&self) -> Option<Resolution> {
        match *self {
            Defuzzifier::Centroid(r)
            | Defuzzifier::Bisector(r)
            | Defuzzifier::MeanOfMaximum(r)
            | Defuzzifier::SmallestOfMaximum(r)
            | Defuzzifier::LargestOfMaximum(r) => Some(r),
            Defuzzifier::CenterAverage | Defuzzifier::WeightedAverage => None,
        }
    }
}

/// What is read off the aggregated set; the resolution is dealt with by the caller.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Statistic {
    Centroid,
    Bisector,
    Mom,
    Som,
    Lom,
}

impl Statistic {
    pub(crate) fn of(d: Defuzzifier) -> Option<Self> {
        Some(match d {
            Defuzzifier::Centroid(_) => Statistic::Centroid,
            Defuzzifier::Bisector(_) => Statistic::Bisector,
            Defuzzifier::MeanOfMaximum(_) => Statistic::Mom,
            Defuzzifier::SmallestOfMaximum(_) => Statistic::Som,
            Defuzzifier::LargestOfMaximum(_) => Statistic::Lom,
            Defuzzifier::CenterAverage | Defuzzifier::WeightedAverage => return None,
        })
    }
}

/// The points a sampled defuzzifier looks at: `x = min + k·dx` (MATLAB, ends included) or
/// `min + (k + ½)·dx` (fuzzylite's midpoints).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Grid<T> {
    min: T,
    max: T,
    dx: T,
    cells: T,
    offset: T,
}

impl<T: Real> Grid<T> {
    /// `n` points over `[min, max]`.
    pub(crate) fn new(min: T, max: T, n: usize, midpoints: bool) -> Self {
        let (cells, offset) = match midpoints {
            true => (T::of(n as f64), T::of(0.5)),
            false => (T::of(n.saturating_sub(1).max(1) as f64), T::zero()),
        };
        Grid {
            min,
            max,
            dx: (max - min) / cells,
            cells,
            offset,
        }
    }

    /// The point at (fractional) index `k`: the textbook `min + (k + offset)·dx`, or where the
    /// span overflows (a universe wider than the largest float) the same point without it.
    #[inline]
    pub(crate) fn x(&self, k: T) -> T {
        let x = if self.dx.is_finite() {
            self.min + (k + self.offset) * self.dx
        } else {
            crate::mf::lerp(self.min, self.max, (k + self.offset) / self.cells)
        };
        // The last end point can round an ulp past `max` (and miss a term ending there).
        x.min(self.max)
    }
}

/// MATLAB's `defuzz` (end-point grids) or fuzzylite's (midpoint grids) on samples `mu[k]` at
/// `grid.x(k)`; `None` when the set is empty.
pub(crate) fn sampled<T: Real>(stat: Statistic, mu: &[T], grid: &Grid<T>) -> Option<T> {
    let midpoints = grid.offset > T::zero();
    let x = |k: usize| grid.x(T::of(k as f64));
    let (mut total, mut moment, mut peak) = (T::zero(), T::zero(), T::zero());
    for (k, &m) in mu.iter().enumerate() {
        total = total + m;
        moment = moment + T::of(k as f64) * m;
        peak = peak.max(m);
    }
    if !(total > T::zero()) {
        return None;
    }
    match stat {
        // Σ x μ / Σ μ with x = min + k dx: the offset is pulled out for precision.
        Statistic::Centroid => Some(grid.x(moment / total)),
        Statistic::Bisector if midpoints => {
            // fuzzylite: the mean of the points whose cumulative share is nearest to ½.
            let half = T::of(0.5);
            let gap = |run: T| (run / total - half).abs();
            let (mut run, mut best) = (T::zero(), T::infinity());
            for &m in mu {
                run = run + m;
                best = best.min(gap(run));
            }
            let (mut run, mut n, mut sum) = (T::zero(), 0usize, T::zero());
            for (k, &m) in mu.iter().enumerate() {
                run = run + m;
                if gap(run) == best {
                    n += 1;
                    sum = sum + x(k);
                }
            }
            (n > 0).then(|| sum / T::of(n as f64))
        }
        Statistic::Bisector => {
            let half = total / (T::one() + T::one());
            let mut run = T::zero();
            mu.iter()
                .position(|&m| {
                    run = run + m;
                    run >= half
                })
                .map(x)
        }
        Statistic::Mom => {
            let (mut n, mut sum) = (0usize, T::zero());
            for (k, _) in mu.iter().enumerate().filter(|(_, m)| **m == peak) {
                n += 1;
                sum = sum + T::of(k as f64);
            }
            Some(grid.x(sum / T::of(n as f64)))
        }
        Statistic::Som => mu.iter().position(|&m| m == peak).map(x),
        Statistic::Lom => mu.iter().rposition(|&m| m == peak).map(x),
    }
}

/// Running statistics of a piecewise-linear function fed piece by piece, left to right.
#[derive(Debug, Clone, Copy)]
pub(crate) struct PieceStats<T> {
    pub(crate) area: T,
    moment: T,
    peak: T,
    som: T,
    lom: T,
    plateau_len: T,
    plateau_moment: T,
}

impl<T: Real> PieceStats<T> {
    pub(crate) fn new() -> Self {
        let z = T::zero();
        PieceStats {
            area: z,
            moment: z,
            peak: z,
            som: z,
            lom: z,
            plateau_len: z,
            plateau_moment: z,
        }
    }

    /// Adds the linear piece from `(x0, y0)` to `(x1, y1)`.
    pub(crate) fn add(&mut self, x0: T, y0: T, x1: T, y1: T) {
        let h = x1 - x0;
        let two = T::one() + T::one();
        let six = T::of(6.0);
        self.area = self.area + (y0 + y1) / two * h;
        self.moment = self.moment + h / six * (x0 * (two * y0 + y1) + x1 * (y0 + two * y1));
        // Pieces are linear, so their maximum is at an end. Values equal to the peak up to a few
        // ulps (clip points evaluated by interpolation) count as the peak.
        let top = y0.max(y1);
        let tol = self.peak.max(top) * T::epsilon() * T::of(64.0);
        if top > self.peak + tol {
            self.peak = top;
            self.som = if y0 >= y1 - tol { x0 } else { x1 };
            self.lom = self.som;
            self.plateau_len = T::zero();
            self.plateau_moment = T::zero();
        }
        if self.peak > T::zero() {
            let at0 = (y0 - self.peak).abs() <= tol;
            let at1 = (y1 - self.peak).abs() <= tol;
            if at0 && at1 {
                self.plateau_len = self.plateau_len + h;
                self.plateau_moment = self.plateau_moment + h * (x0 + x1) / two;
            }
            if at0 {
                self.som = self.som.min(x0);
                self.lom = self.lom.max(x0);
            }
            if at1 {
                self.som = self.som.min(x1);
                self.lom = self.lom.max(x1);
            }
        }
    }

    /// The statistic, `None` for an empty set. The bisector needs a second pass
    /// ([`bisector_in_piece`]), so it is not answered here.
    pub(crate) fn finish(&self, stat: Statistic) -> Option<T> {
        if !(self.area > T::zero()) || !(self.peak > T::zero()) {
            return None;
        }
        let two = T::one() + T::one();
        match stat {
            Statistic::Centroid => Some(self.moment / self.area),
            Statistic::Mom if self.plateau_len > T::zero() => {
                Some(self.plateau_moment / self.plateau_len)
            }
            Statistic::Mom => Some((self.som + self.lom) / two),
            Statistic::Som => Some(self.som),
            Statistic::Lom => Some(self.lom),
            Statistic::Bisector => None,
        }
    }
}

/// Within the linear piece `(x0, y0)–(x1, y1)`, the x where the area from `x0` reaches `r`
/// (`0 ≤ r ≤` the piece's area).
pub(crate) fn bisector_in_piece<T: Real>(x0: T, y0: T, x1: T, y1: T, r: T) -> T {
    let h = x1 - x0;
    if !(h > T::zero()) {
        return x0;
    }
    let s = (y1 - y0) / h;
    let two = T::one() + T::one();
    // Solve y0 u + s u²/2 = r in the cancellation-free form u = 2r / (y0 + √(y0² + 2 s r)).
    let disc = (y0 * y0 + two * s * r).max(T::zero());
    let den = y0 + disc.sqrt();
    let u = if den > T::zero() {
        two * r / den
    } else {
        T::zero()
    };
    (x0 + u).min(x1)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sampled_statistics_of_a_plateau() {
        // μ = 0 0 1 1 1 0 at x = 0..5.
        let mu = [0.0, 0.0, 1.0, 1.0, 1.0, 0.0f64];
        let grid = Grid::new(0.0, 5.0, 6, false);
        assert_eq!(sampled(Statistic::Centroid, &mu, &grid), Some(3.0));
        assert_eq!(sampled(Statistic::Mom, &mu, &grid), Some(3.0));
        assert_eq!(sampled(Statistic::Som, &mu, &grid), Some(2.0));
        assert_eq!(sampled(Statistic::Lom, &mu, &grid), Some(4.0));
        assert_eq!(sampled(Statistic::Bisector, &mu, &grid), Some(3.0));
        assert_eq!(
            sampled(
                Statistic::Centroid,
                &[0.0f64; 4],
                &Grid::new(0.0, 3.0, 4, false)
            ),
            None
        );
    }

    #[test]
    fn piece_stats_of_a_symmetric_triangle() {
        let mut s = PieceStats::new();
        s.add(0.0, 0.0, 1.0, 1.0f64);
        s.add(1.0, 1.0, 2.0, 0.0);
        assert!((s.finish(Statistic::Centroid).unwrap_or(f64::NAN) - 1.0).abs() < 1e-15);
        assert_eq!(s.finish(Statistic::Mom), Some(1.0));
        assert!((bisector_in_piece(0.0, 0.0, 1.0, 1.0, 0.5) - 1.0f64).abs() < 1e-15);
    }
}
