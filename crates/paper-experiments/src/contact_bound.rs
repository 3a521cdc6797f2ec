//! How precisely the fingertip's readings place a contact, in principle: the
//! Cramér–Rao bound of the simulator's own forward model for a single-cell tap, and the share
//! of taps an efficient locator would put on the right one of the 24 cells.
//!
//! The readings of a tap are what the dataset keeps: every frame from 30 ms before to 90 ms
//! after onset, and the mean of the frames 250–350 ms into the hold. Each sensor `k` reads
//!
//! ```text
//! μ_k(t) = b_k + R_k(x, y, F) · (1 − exp(−(t − t0 − d_k(x, y)) / τ))   for t > t0 + d_k, else b_k
//! ```
//!
//! with hand-sim's law ([`LawParams`]: the steady rise `R_k` of a cell pressed with force `F`
//! at the shift `(x, y)` off its centre, the arrival delay `d_k`, the time constant `τ`) plus
//! Gaussian noise of the MS5611's datasheet RMS at the OSR, independent per reading. The
//! unknowns are the shift, the force, the onset `t0` and the three baselines; the Fisher
//! information of those seven over the readings, inverted, bounds the covariance of any
//! unbiased estimate of the shift, and an efficient estimator (maximum likelihood, at this
//! signal-to-noise ratio) attains it. Its 24-area accuracy is then the probability that the
//! estimate, Gaussian with that covariance around the true point, stays in the true cell.
//!
//! What this grants the locator, so the figure is a ceiling for what it assumes: the law
//! itself (a learned locator only has taps), and that the contact is one cell (it must also
//! tell the Figure 7 shapes apart). What it leaves out: the chip model also puts the
//! temperature reading's noise into the decoded pressure (≈ 3 % more spread at OSR 256), and
//! the three sensors are converted one after another within a frame, not at its stamp; the
//! bound takes every reading at its frame's time.

use aot_locate::CELLS;
use baro_drivers::Osr;
use hand_sim::fingertip::{Cell, CellSet, ContactPatch, LawParams, geometry};
use nalgebra::SMatrix;

/// The unknowns: shift x, y (mm), force (N), onset (ms), three baselines (Pa).
const PARAMS: usize = 7;
/// Central-difference steps of the unknowns: small against their effect, large against f64
/// rounding of readings near 10⁵ Pa.
const STEPS: [f64; PARAMS] = [1e-4, 1e-4, 1e-4, 1e-4, 1e-3, 1e-3, 1e-3];

/// When the readings of a tap are taken.
#[derive(Debug, Clone, PartialEq)]
pub struct Sampling {
    /// The frames of the kept series, ms from onset.
    pub series_ms: Vec<f64>,
    /// The frames averaged into the held pressure, ms from onset.
    pub held_ms: Vec<f64>,
    /// Reading noise, Pa RMS.
    pub noise_pa: f64,
}

impl Sampling {
    /// The dataset's sampling at `osr`, from one tap's series times `series_us` (µs from onset,
    /// ascending): its frames, and the frames of the same period that fall 250–350 ms into the
    /// hold; the noise is the MS5611's datasheet RMS at `osr`. `None` for fewer than two frames.
    pub fn of_series(osr: Osr, series_us: &[i64]) -> Option<Sampling> {
        let (first, last) = (*series_us.first()?, *series_us.last()?);
        let frames = series_us.len().checked_sub(1).filter(|&n| n > 0)?;
        let period_ms = (last - first) as f64 / 1000.0 / frames as f64;
        let series_ms: Vec<f64> = series_us.iter().map(|&t| t as f64 / 1000.0).collect();
        let start = first as f64 / 1000.0;
        let held_ms = (0..)
            .map(|i| start + f64::from(i) * period_ms)
            .skip_while(|&t| t < 250.0)
            .take_while(|&t| t <= 350.0)
            .collect();
        Some(Sampling {
            series_ms,
            held_ms,
            noise_pa: f64::from(osr.pressure_noise_rms_mbar()) * 100.0,
        })
    }
}

/// The bound for one single-cell tap.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TapBound {
    /// Standard deviation of an efficient estimate of the contact's x and y, mm.
    pub sigma_mm: [f64; 2],
    /// Correlation of the two.
    pub correlation: f64,
    /// Probability that the estimate falls in the touched cell.
    pub hit_probability: f64,
}

/// The noise-free readings of a tap on `cell` at the unknowns `p`, in the order the Fisher
/// information sums them: per sensor, its series, then its held mean.
fn readings(law: &LawParams, cell: Cell, p: &[f64; PARAMS], s: &Sampling, out: &mut Vec<f64>) {
    out.clear();
    let patch = ContactPatch {
        cells: CellSet::EMPTY.with(cell),
        force_n: p[2],
        offset_mm: [p[0], p[1]],
    };
    let rise_pa = law.steady_rise_hpa(&patch).map(|r| r * 100.0);
    for (k, rise) in rise_pa.into_iter().enumerate() {
        let start = p[3] + law.arrival_delay_ms(&patch, k);
        let at = |t: f64| {
            let since = (t - start).max(0.0);
            p[4 + k] + rise * (1.0 - (-since / law.time_constant_ms).exp())
        };
        out.extend(s.series_ms.iter().map(|&t| at(t)));
        let held = s.held_ms.iter().map(|&t| at(t)).sum::<f64>() / s.held_ms.len().max(1) as f64;
        out.push(held);
    }
}

/// The Cramér–Rao bound of a tap on `cell` shifted by `shift_mm`, pressed with `force_n`,
/// read as `sampling` says. `None` when the information is singular (a contact no sensor
/// feels).
pub fn tap_bound(
    law: &LawParams,
    cell: Cell,
    shift_mm: [f64; 2],
    force_n: f64,
    sampling: &Sampling,
) -> Option<TapBound> {
    let truth = [shift_mm[0], shift_mm[1], force_n, 0.0, 1.0e5, 1.0e5, 1.0e5];
    let (mut up, mut down) = (Vec::new(), Vec::new());
    let mut columns: Vec<Vec<f64>> = Vec::with_capacity(PARAMS);
    for (j, h) in STEPS.into_iter().enumerate() {
        let (mut a, mut b) = (truth, truth);
        a[j] += h;
        b[j] -= h;
        readings(law, cell, &a, sampling, &mut up);
        readings(law, cell, &b, sampling, &mut down);
        columns.push(
            up.iter()
                .zip(&down)
                .map(|(u, d)| (u - d) / (2.0 * h))
                .collect(),
        );
    }
    // A held mean of n frames has 1/n of one frame's variance.
    let per_sensor = sampling.series_ms.len() + 1;
    let weight = |i: usize| {
        let n = if i % per_sensor == per_sensor - 1 {
            sampling.held_ms.len().max(1) as f64
        } else {
            1.0
        };
        n / sampling.noise_pa.powi(2)
    };
    let information = SMatrix::<f64, PARAMS, PARAMS>::from_fn(|a, b| {
        (0..columns[a].len())
            .map(|i| weight(i) * columns[a][i] * columns[b][i])
            .sum()
    });
    let covariance = information.cholesky()?.inverse();
    let (vx, vy, cxy) = (covariance[(0, 0)], covariance[(1, 1)], covariance[(0, 1)]);
    let sigma_mm = [vx.sqrt(), vy.sqrt()];
    let correlation = (cxy / (sigma_mm[0] * sigma_mm[1])).clamp(-1.0, 1.0);
    let half = geometry::PITCH_MM / 2.0;
    let hit_probability = box_probability(
        sigma_mm,
        correlation,
        [-half - shift_mm[0], half - shift_mm[0]],
        [-half - shift_mm[1], half - shift_mm[1]],
    );
    Some(TapBound {
        sigma_mm,
        correlation,
        hit_probability,
    })
}

/// Probability that a centred bivariate normal (standard deviations `sigma`, correlation
/// `rho`) falls in the box `x ∈ xs`, `y ∈ ys`: Simpson's rule over x (2000 intervals, ±9 σ at
/// most) of the x density times the conditional probability of y.
fn box_probability(sigma: [f64; 2], rho: f64, xs: [f64; 2], ys: [f64; 2]) -> f64 {
    let phi = |z: f64| 0.5 * libm::erfc(-z / core::f64::consts::SQRT_2);
    let (lo, hi) = (xs[0].max(-9.0 * sigma[0]), xs[1].min(9.0 * sigma[0]));
    if hi <= lo {
        return 0.0;
    }
    let conditional_sd = sigma[1] * (1.0 - rho * rho).max(1e-12).sqrt();
    let f = |x: f64| {
        let z = x / sigma[0];
        let density = (-0.5 * z * z).exp() / (sigma[0] * (2.0 * core::f64::consts::PI).sqrt());
        let mean = rho * sigma[1] * z;
        density * (phi((ys[1] - mean) / conditional_sd) - phi((ys[0] - mean) / conditional_sd))
    };
    let n = 2000;
    let h = (hi - lo) / f64::from(n);
    let inner: f64 = (1..n)
        .map(|i| f(lo + f64::from(i) * h) * if i % 2 == 1 { 4.0 } else { 2.0 })
        .sum();
    (h / 3.0 * (f(lo) + inner + f(hi))).clamp(0.0, 1.0)
}

/// The bound over a set of single-cell taps.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SetBound {
    /// Taps bounded.
    pub taps: usize,
    /// Mean hit probability: the 24-area accuracy an efficient locator expects.
    pub accuracy: f64,
    /// Median of the larger of each tap's two standard deviations, mm.
    pub median_sigma_mm: f64,
    /// Largest standard deviation of any tap, mm.
    pub max_sigma_mm: f64,
}

/// The bound over the single-cell taps `taps` (cell index 0–23, shift mm, force N) read as
/// `sampling` says, with hand-sim's calibrated law. Taps whose information is singular count
/// as misses with an infinite spread.
pub fn set_bound(taps: &[(usize, [f64; 2], f64)], sampling: &Sampling) -> SetBound {
    let law = LawParams::CALIBRATED;
    let mut sigmas = Vec::with_capacity(taps.len());
    let mut hits = 0.0;
    for &(cell, shift, force) in taps {
        let bound =
            Cell::from_index(cell % CELLS).and_then(|c| tap_bound(&law, c, shift, force, sampling));
        match bound {
            Some(b) => {
                hits += b.hit_probability;
                sigmas.push(b.sigma_mm[0].max(b.sigma_mm[1]));
            }
            None => sigmas.push(f64::INFINITY),
        }
    }
    sigmas.sort_by(f64::total_cmp);
    SetBound {
        taps: taps.len(),
        accuracy: if taps.is_empty() {
            0.0
        } else {
            hits / taps.len() as f64
        },
        median_sigma_mm: sigmas.get(sigmas.len() / 2).copied().unwrap_or(f64::NAN),
        max_sigma_mm: sigmas.last().copied().unwrap_or(f64::NAN),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn box_probability_matches_the_normal_tables() {
        // Independent axes: the product of 1-D probabilities; ±1.96 σ holds 95 % each.
        let p = box_probability([1.0, 2.0], 0.0, [-1.96, 1.96], [-3.92, 3.92]);
        assert!((p - 0.95 * 0.95).abs() < 1e-4, "{p}");
        // Half a line: a quarter of the plane for any correlation sign at 0.
        let q = box_probability([1.0, 1.0], 0.0, [0.0, 50.0], [0.0, 50.0]);
        assert!((q - 0.25).abs() < 1e-6, "{q}");
        // Perfectly correlated axes and a quadrant: x > 0 implies y > 0, so one half.
        let r = box_probability([1.0, 1.0], 0.999_999, [0.0, 50.0], [0.0, 50.0]);
        assert!((r - 0.5).abs() < 1e-3, "{r}");
        assert_eq!(
            box_probability([1.0, 1.0], 0.0, [20.0, 30.0], [0.0, 1.0]),
            0.0
        );
    }

    fn sampling(noise_pa: f64) -> Sampling {
        // OSR 256's dataset frames: every 1.212 ms from −29.45 ms.
        let series_us: Vec<i64> = (0..99).map(|i| -29_450 + 1212 * i).collect();
        Sampling {
            noise_pa,
            ..Sampling::of_series(Osr::Osr256, &series_us).expect("frames")
        }
    }

    #[test]
    fn the_dataset_sampling_is_rebuilt() {
        let s = sampling(6.5);
        assert_eq!(s.series_ms.len(), 99);
        // 100 ms of 1.212 ms frames.
        assert!((82..=84).contains(&s.held_ms.len()), "{}", s.held_ms.len());
        assert!(s.held_ms.iter().all(|t| (250.0..=350.0).contains(t)));
        let osr = Sampling::of_series(Osr::Osr256, &[0, 1212]).expect("two frames");
        assert!((osr.noise_pa - 6.5).abs() < 1e-4, "{}", osr.noise_pa);
        assert_eq!(Sampling::of_series(Osr::Osr256, &[5]), None);
    }

    #[test]
    fn the_spread_scales_with_the_noise_and_a_centred_tap_is_placed() {
        let law = LawParams::CALIBRATED;
        let cell = Cell::new(2, 3).expect("cell");
        let force = 5.0 * hand_sim::fingertip::KGF_N;
        let quiet = tap_bound(&law, cell, [0.0, 0.0], force, &sampling(6.5)).expect("bound");
        let loud = tap_bound(&law, cell, [0.0, 0.0], force, &sampling(65.0)).expect("bound");
        // The bound is linear in the noise.
        for a in 0..2 {
            let ratio = loud.sigma_mm[a] / quiet.sigma_mm[a];
            assert!((ratio - 10.0).abs() < 1e-6, "{ratio}");
        }
        assert!(quiet.hit_probability > 0.999, "{quiet:?}");
        // A tap 0.1 mm inside its cell's edge with σ ≥ 0.1 mm is a coin toss or worse.
        let edge = tap_bound(&law, cell, [1.4, 0.0], force, &sampling(650.0)).expect("bound");
        assert!(
            edge.sigma_mm[0] > 0.1 && edge.hit_probability < 0.9,
            "{edge:?}"
        );
    }
}
