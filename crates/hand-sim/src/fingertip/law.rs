//! How a contact raises each sensor's pressure: a spatial kernel, a saturating force response
//! and a first-order rise that starts later the farther the sensor.
//!
//! Steady state, for sensor `k` and a patch of `n` cells sharing force `F`:
//!
//! ```text
//! u_k   = Σ_cells (F / n) · exp(−Δx²/2σx² − Δy²/2σy²)          effective load on sensor k (N)
//! rise_k = g_k · ( a·u_k + S·(1 − exp(−(u_k / u0)^m)) )        hPa
//! ```
//!
//! The linear term carries the light, whole-pad loads of seed 000 Table 1 (grams); the
//! Weibull-shaped term the convex-then-saturating growth of Table 2 between 5, 7 and 9 kgf on one
//! cell. The kernel is anisotropic because Table 2 is: a press on row 1 at the far left still
//! raises the right-hand sensor 1 by 35 hPa (wide spread along a row, σx), while sensor 2, nine
//! millimetres lower, rises only 1.3…3.3 hPa (narrower spread across rows, σy); an isotropic
//! kernel fits one or the other, never both (docs/sim-calibration/fingertip.md). `g_k` absorbs sensor-to-sensor spread (Table 1's three sensors rise 1.22 / 1.04 / 1.14 hPa
//! for the same 200 gf). The parameters are fitted by least squares to
//! `fixtures/derived/seed000_table{1,2}_rise.csv` (see [`LawParams::CALIBRATED`] and
//! `docs/sim-calibration/fingertip.md`, which lists the residuals).
//!
//! Timing (not given by the paper, an assumption sized so Arrival-of-Time is measurable at the
//! MS5611's conversion rates): sensor `k` starts rising `τ0 + d_k / v` after contact, where `d_k`
//! is its distance to the patch centroid (cell centres and centroid both moved by the patch's
//! `offset_mm`), and approaches its steady rise with time constant `T`.

use super::contact::ContactPatch;
use super::geometry::{Cell, SENSORS};

/// Every parameter of the law.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LawParams {
    /// Sensor positions in the pad plane, mm (sensor 1, 2, 3).
    pub sensors_mm: [[f64; 2]; SENSORS],
    /// Width σx of the spatial kernel along a row, mm.
    pub sigma_x_mm: f64,
    /// Width σy of the spatial kernel across rows, mm.
    pub sigma_y_mm: f64,
    /// Linear response `a`, hPa per newton of effective load.
    pub linear_hpa_per_n: f64,
    /// Saturation level `S` of the non-linear response, hPa.
    pub saturation_hpa: f64,
    /// Scale `u0` of the non-linear response, newton.
    pub scale_n: f64,
    /// Shape `m` of the non-linear response (> 1: convex at first).
    pub exponent: f64,
    /// Per-sensor gain `g_k` (sensor 1 is the reference, 1.0).
    pub gains: [f64; SENSORS],
    /// Delay before the nearest possible sensor starts to rise, ms.
    pub delay_base_ms: f64,
    /// Speed at which the pressure front crosses the pad, mm per ms.
    pub front_speed_mm_per_ms: f64,
    /// Time constant of the first-order rise and fall, ms.
    pub time_constant_ms: f64,
}

impl LawParams {
    /// Steady pressure rise of each sensor under `patch`, hPa.
    ///
    /// ```
    /// use hand_sim::fingertip::{Cell, CellSet, ContactPatch, LawParams};
    /// let law = LawParams::CALIBRATED;
    /// let patch = ContactPatch::from_kgf(CellSet::EMPTY.with(Cell::new(1, 1).unwrap()), 9.0);
    /// let rise = law.steady_rise_hpa(&patch);
    /// assert!(rise[2] > rise[0] && rise[0] > rise[1]); // area 1.1: sensor 3, then 1, then 2
    /// ```
    pub fn steady_rise_hpa(&self, patch: &ContactPatch) -> [f64; SENSORS] {
        let n = patch.cells.len();
        // NaN, zero and negative forces all press nothing.
        if n == 0 || patch.force_n.is_nan() || patch.force_n <= 0.0 {
            return [0.0; SENSORS];
        }
        let per_cell = patch.force_n.min(MAX_FORCE_N) / f64::from(n);
        core::array::from_fn(|k| {
            let u: f64 = patch
                .cells
                .iter()
                .map(|c| {
                    let ([cx, cy], [sx, sy]) = (Cell::from(c).centre_mm(), self.sensors_mm[k]);
                    let (x, y) = (cx + patch.offset_mm[0], cy + patch.offset_mm[1]);
                    let e = (x - sx).powi(2) / (2.0 * self.sigma_x_mm.powi(2))
                        + (y - sy).powi(2) / (2.0 * self.sigma_y_mm.powi(2));
                    per_cell * (-e).exp()
                })
                .sum();
            let saturating =
                self.saturation_hpa * (1.0 - (-(u / self.scale_n).powf(self.exponent)).exp());
            self.gains[k] * (self.linear_hpa_per_n * u + saturating)
        })
    }

    /// When sensor `k` starts to rise after a contact at `patch` begins, ms.
    pub fn arrival_delay_ms(&self, patch: &ContactPatch, k: usize) -> f64 {
        let centroid = patch.centroid_mm();
        self.delay_base_ms + dist2(centroid, self.sensors_mm[k]).sqrt() / self.front_speed_mm_per_ms
    }
}

/// Forces are clamped here before the law sees them: 100 kgf, ten times the paper's largest,
/// far into saturation, so any finite or infinite input gives a finite rise.
pub const MAX_FORCE_N: f64 = 100.0 * super::contact::KGF_N;

fn dist2(a: [f64; 2], b: [f64; 2]) -> f64 {
    (a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)
}
