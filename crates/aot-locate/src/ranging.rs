//! Translation-aware area scores from eq. 3's ingredients: arrival times read as ranges.
//!
//! Eq. 3 ranks sensors (its argmax is always the area nearest the dominant sensor, see
//! `docs/contact-location.md`); this scorer places the contact *between* them. A pressure
//! front leaves the contact and reaches sensor `k` after a time that grows with its distance
//! `r_k`, and the detector then needs a little longer to see a small rise cross its threshold
//! than a large one:
//!
//! ```text
//! t_k ≈ a + b·r_k + c·L_k,     L_k = −ln(1 − θ / P_k)   (a first-order rise of size P_k
//!                                                       crossing the threshold θ)
//! ```
//!
//! `a` (µs), `b` (µs per mm) and `c` (µs) are fitted on taps whose contact is known
//! ([`RangingFit`]); `t_k` counts from contact onset, as [`ArrivalEvent`] defines it. Each
//! arrived sensor then gives a range `ρ_k = (t_k − a − c·L_k) / b`; from the linearised fix
//! (or the pad centre when fewer than three sensors arrived) a few damped Gauss–Newton steps
//! find the pad point whose distances best match the ranges, and area `n` scores
//! `−|p − centre_n|²` (mm²), so the argmax is the area holding the point on a regular grid.

use crate::geometry::{AREAS, Geometry, SENSORS};
use crate::lag::threshold_lag;
use crate::score::{AotError, ArrivalEvent, Scores};
use crate::trilateration::BOUND_MM;

/// Gauss–Newton steps from the pad centre (fewer than three ranges, or collinear sensors):
/// six converge on a fingertip-sized pad (18 × 12 mm, 3 mm cells).
const ITERATIONS_FROM_CENTRE: usize = 6;
/// Gauss–Newton steps from the closed-form start (three ranges): one reaches the held-out
/// accuracy of two (and of six from the centre) on simulated taps of that pad, and each step is
/// about a third of a localisation's cost (a square root and two divisions in series).
const ITERATIONS_FROM_LINEAR: usize = 1;
/// Levenberg damping of the 2 × 2 normal matrix: keeps a step defined when fewer than two
/// sensors (or collinear ones) constrain the position.
const DAMPING: f64 = 1e-3;

/// The fitted range model of arrival times (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ranging {
    delay_us: f64,
    us_per_mm: f64,
    // 1 / `us_per_mm`, `a / b` and `c / b`: a range is `t/b − a/b − (c/b)·L`, products and
    // differences only, with the lag's term last on the critical path.
    mm_per_us: f64,
    delay_mm: f64,
    lag_mm: f64,
    lag_us: f64,
    threshold_pa: f32,
}

/// Why a [`Ranging`] model was refused.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum RangingError {
    /// `b` (µs per mm) is not finite and positive: distances would not order times.
    Slope,
    /// The delay `a`, the lag coefficient `c` or the threshold `θ` is not finite, or `θ` is
    /// negative.
    Offset,
}

impl core::fmt::Display for RangingError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            RangingError::Slope => f.write_str("µs per mm must be finite and positive"),
            RangingError::Offset => {
                f.write_str("delay, lag and threshold must be finite, threshold ≥ 0")
            }
        }
    }
}

impl Ranging {
    /// A model `t = delay_us + us_per_mm·r + lag_us·L` for a detector threshold `threshold_pa`.
    ///
    /// ```
    /// use aot_locate::{AreaGrid, ArrivalEvent, Geometry, Ranging};
    /// // An 18 × 12 mm pad with its sensors in an inverted triangle.
    /// let sensors = [[4.5, 1.5], [0.0, -4.5], [-4.5, 1.5]];
    /// let pad = Geometry::new(sensors, AreaGrid { width_mm: 18.0, height_mm: 12.0 }).unwrap();
    /// // 2 ms until the front leaves, 2.5 ms per mm, no threshold lag.
    /// let model = Ranging::new(2_000.0, 2_500.0, 0.0, 30.0).unwrap();
    /// // A press at (0, −4) mm, the bottom-middle area: sensor 2 is 0.5 mm away, sensors 1
    /// // and 3 are √(4.5² + 5.5²) ≈ 7.11 mm away.
    /// let e = ArrivalEvent {
    ///     pressure_pa: [500.0, 2_000.0, 500.0],
    ///     arrival_us: [Some(19_770), Some(3_250), Some(19_770)],
    /// };
    /// let p = model.position_mm(&pad, &e).unwrap();
    /// assert!(p[0].abs() < 0.05 && (p[1] + 4.0).abs() < 0.05, "{p:?}");
    /// assert_eq!(model.scores(&pad, &e).unwrap().argmax(), 7);
    /// assert!(Ranging::new(0.0, 0.0, 0.0, 30.0).is_err());
    /// ```
    pub fn new(
        delay_us: f32,
        us_per_mm: f32,
        lag_us: f32,
        threshold_pa: f32,
    ) -> Result<Ranging, RangingError> {
        if !(us_per_mm.is_finite() && us_per_mm > 0.0) {
            return Err(RangingError::Slope);
        }
        let finite = delay_us.is_finite() && lag_us.is_finite() && threshold_pa.is_finite();
        if !(finite && threshold_pa >= 0.0) {
            return Err(RangingError::Offset);
        }
        Ok(Ranging {
            delay_us: f64::from(delay_us),
            us_per_mm: f64::from(us_per_mm),
            mm_per_us: 1.0 / f64::from(us_per_mm),
            delay_mm: f64::from(delay_us) / f64::from(us_per_mm),
            lag_mm: f64::from(lag_us) / f64::from(us_per_mm),
            lag_us: f64::from(lag_us),
            threshold_pa,
        })
    }

    /// `a`, µs.
    pub fn delay_us(&self) -> f64 {
        self.delay_us
    }

    /// `b`, µs per mm.
    pub fn us_per_mm(&self) -> f64 {
        self.us_per_mm
    }

    /// `c`, µs per unit of `L = −ln(1 − θ/P)`.
    pub fn lag_us(&self) -> f64 {
        self.lag_us
    }

    /// The pad point (mm) whose distances to the arrived sensors best match their ranges.
    ///
    /// Defined at the edges:
    /// - a sensor that never arrived (`None`) gives no range and drops out; with two ranges
    ///   the circles cross twice, mirror images across the line through the two sensors, and
    ///   the point is the crossing farther from the silent sensor (it felt nothing, so the
    ///   contact is far from it; the search starts on that side of the line); with one range,
    ///   the point of its circle nearest the pad centre (the start of the search);
    /// - no sensor arrived: [`AotError::NoArrival`]; a NaN or infinite pressure:
    ///   [`AotError::NonFinitePressure`], as [`crate::eq3`];
    /// - zero and equal times are ordinary values (a time before `a` is a negative range,
    ///   which pulls the point onto the sensor); no division by `r` or `t` takes place, and a
    ///   point exactly on a sensor takes no direction from it in that step;
    /// - a pressure at or under `θ` gets the largest lag, `ln 100`;
    /// - the point stays within 10 m of the pad centre, so any finite input gives a finite
    ///   point.
    pub fn position_mm(
        &self,
        geometry: &Geometry,
        event: &ArrivalEvent,
    ) -> Result<[f64; 2], AotError> {
        if let Some(sensor) = event.pressure_pa.iter().position(|p| !p.is_finite()) {
            return Err(AotError::NonFinitePressure { sensor });
        }
        if event.arrival_us.iter().all(Option::is_none) {
            return Err(AotError::NoArrival);
        }
        // Sensors in a canonical order (by position, fixed per pad and precomputed with it;
        // by the inputs too only where two sensors share a position): every sum below runs
        // in that order, so renumbering the sensors cannot change a bit.
        let fix = geometry.trilateration();
        let order = fix.order(geometry.sensors_mm(), &event.arrival_us, &event.pressure_pa);
        let range_of = |k: usize| {
            event.arrival_us[k].map(|t| {
                (f64::from(t) * self.mm_per_us - self.delay_mm)
                    - self.lag_mm * self.lag(event.pressure_pa[k])
            })
        };
        // Written out: `order.map` compiles to three out-of-line calls here.
        let range = [range_of(order[0]), range_of(order[1]), range_of(order[2])];
        let sensors = &fix.sensors;
        // Start: with three ranges the closed-form (linearised) fix, else the pad's centre;
        // either is the same for any sensor order.
        let linear = match (fix.linear, range) {
            (Some(l), [Some(r0), Some(r1), Some(r2)]) => l.solve([r0, r1, r2]),
            _ => None,
        };
        let (mut p, iterations) = match linear {
            Some(p) => (p, ITERATIONS_FROM_LINEAR),
            None => (start(fix.centre, sensors, &range), ITERATIONS_FROM_CENTRE),
        };
        for _ in 0..iterations {
            // Per sensor: the unit vector from it to p and the range residual; sums in the
            // canonical order.
            let mut terms = [[0.0f64; 5]; SENSORS];
            for (k, term) in terms.iter_mut().enumerate() {
                let Some(rho) = range[k] else { continue };
                let (dx, dy) = (p[0] - sensors[k][0], p[1] - sensors[k][1]);
                let d2 = dx * dx + dy * dy;
                // On (or within 1e-154 mm of) the sensor: no direction from it.
                if d2 <= f64::MIN_POSITIVE {
                    continue;
                }
                // The square root and the division run side by side, not one after the
                // other: u uᵀ = (dx, dy)(dx, dy)ᵀ / d², u·(d − ρ) = (dx, dy)·(1 − ρ/d).
                let inv_d2 = 1.0 / d2;
                let inv_d = libm::sqrt(d2) * inv_d2;
                let w = 1.0 - rho * inv_d;
                *term = [
                    dx * dx * inv_d2,
                    dx * dy * inv_d2,
                    dy * dy * inv_d2,
                    dx * w,
                    dy * w,
                ];
            }
            let sum = |j: usize| (terms[0][j] + terms[1][j]) + terms[2][j];
            let (hxx, hxy, hyy) = (sum(0) + DAMPING, sum(1), sum(2) + DAMPING);
            let (gx, gy) = (sum(3), sum(4));
            let inv_det = 1.0 / (hxx * hyy - hxy * hxy);
            let step = [
                (hyy * gx - hxy * gy) * inv_det,
                (hxx * gy - hxy * gx) * inv_det,
            ];
            if !(step[0].is_finite() && step[1].is_finite()) {
                break;
            }
            p = [0, 1].map(|j| (p[j] - step[j]).clamp(-BOUND_MM, BOUND_MM));
        }
        Ok(away_from_silent(p, sensors, &range))
    }

    /// Scores for the nine areas: `−|p − centre_n|²`, mm², with `p` from
    /// [`Ranging::position_mm`] (same errors and edge cases). Larger is better; on a regular
    /// grid the argmax is the area holding `p`.
    pub fn scores(&self, geometry: &Geometry, event: &ArrivalEvent) -> Result<Scores, AotError> {
        let p = self.position_mm(geometry, event)?;
        let centres = &geometry.trilateration().centres;
        Ok(Scores::from_values(core::array::from_fn::<f64, AREAS, _>(
            |n| {
                let dx = p[0] - centres[n][0];
                let dy = p[1] - centres[n][1];
                -(dx * dx + dy * dy)
            },
        )))
    }

    /// `L = −ln(1 − θ/P)` for a held rise `P` (see the module docs).
    fn lag(&self, pressure_pa: f32) -> f64 {
        f64::from(threshold_lag(self.threshold_pa, pressure_pa))
    }
}

/// Least-squares fit of [`Ranging`]'s `a`, `b` and `c` from taps whose contact position is
/// known, without allocation: it keeps the 3 × 3 normal equations of `t_k = a + b·r_k + c·L_k`
/// over every arrived sensor.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RangingFit {
    threshold_pa: f32,
    // Normal matrix of the rows (1, r, L) and right-hand side Σ (1, r, L)·t.
    xx: [[f64; 3]; 3],
    xt: [f64; 3],
    taps: u32,
}

impl RangingFit {
    /// An empty fit for a detector with threshold `threshold_pa`.
    pub fn new(threshold_pa: f32) -> RangingFit {
        RangingFit {
            threshold_pa,
            xx: [[0.0; 3]; 3],
            xt: [0.0; 3],
            taps: 0,
        }
    }

    /// Adds one training tap: its event and each sensor's distance to the true contact, mm.
    /// A tap with a non-finite pressure or distance is skipped whole.
    pub fn push(&mut self, event: &ArrivalEvent, distances_mm: [f32; SENSORS]) {
        let finite = event
            .pressure_pa
            .iter()
            .chain(&distances_mm)
            .all(|v| v.is_finite());
        if !finite || event.arrival_us.iter().all(Option::is_none) {
            return;
        }
        let sensors = event
            .arrival_us
            .iter()
            .zip(distances_mm)
            .zip(event.pressure_pa);
        for ((t, d), p) in sensors {
            let Some(t) = t else { continue };
            let row = [
                1.0,
                f64::from(d),
                f64::from(threshold_lag(self.threshold_pa, p)),
            ];
            for (xx, ri) in self.xx.iter_mut().zip(row) {
                for (x, rj) in xx.iter_mut().zip(row) {
                    *x += ri * rj;
                }
            }
            for (x, ri) in self.xt.iter_mut().zip(row) {
                *x += ri * f64::from(*t);
            }
        }
        self.taps += 1;
    }

    /// Taps that contributed.
    pub fn taps(&self) -> u32 {
        self.taps
    }

    /// The fitted model, if the taps determine it (a non-singular system and `b > 0`).
    pub fn finish(&self) -> Option<Ranging> {
        let det3 = |m: [[f64; 3]; 3]| {
            m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
                - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
                + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
        };
        let det = det3(self.xx);
        // Cramer's rule: column i of the normal matrix replaced by the right-hand side.
        let solve = |i: usize| {
            let mut m = self.xx;
            for (row, rhs) in m.iter_mut().zip(self.xt) {
                row[i] = rhs;
            }
            det3(m) / det
        };
        let scale = self.xx[0][0] * self.xx[1][1] * self.xx[2][2];
        if !(det.is_finite() && det > 1e-12 * scale) {
            return None;
        }
        Ranging::new(
            solve(0) as f32,
            solve(1) as f32,
            solve(2) as f32,
            self.threshold_pa,
        )
        .ok()
    }
}

/// With exactly one silent sensor: (silent, arrived, arrived), in canonical order.
fn one_silent(range: &[Option<f64>; SENSORS]) -> Option<(usize, usize, usize)> {
    match range {
        [None, Some(_), Some(_)] => Some((0, 1, 2)),
        [Some(_), None, Some(_)] => Some((1, 0, 2)),
        [Some(_), Some(_), None] => Some((2, 0, 1)),
        _ => None,
    }
}

/// Where the search starts without a linear fix: the pad centre, except with exactly one
/// silent sensor, where it starts on the far side of the two arrived sensors' line from the
/// silent one (their midpoint, moved half their distance along the normal), so the search
/// finds the crossing on that side even when the centre lies on the line.
fn start(
    centre: [f64; 2],
    sensors: &[[f64; 2]; SENSORS],
    range: &[Option<f64>; SENSORS],
) -> [f64; 2] {
    let Some((s, a, b)) = one_silent(range) else {
        return centre;
    };
    let mid = [0, 1].map(|j| (sensors[a][j] + sensors[b][j]) / 2.0);
    let normal = [sensors[a][1] - sensors[b][1], sensors[b][0] - sensors[a][0]];
    let away = (mid[0] - sensors[s][0]) * normal[0] + (mid[1] - sensors[s][1]) * normal[1];
    let sign = if away < 0.0 { -0.5 } else { 0.5 };
    [0, 1].map(|j| mid[j] + sign * normal[j])
}

/// With exactly one silent sensor, `p` or its mirror image across the line through the two
/// arrived sensors, whichever is farther from the silent one (`p` on a tie): both match the
/// two ranges equally, and a sensor that felt nothing is the far one. Otherwise `p`.
fn away_from_silent(
    p: [f64; 2],
    sensors: &[[f64; 2]; SENSORS],
    range: &[Option<f64>; SENSORS],
) -> [f64; 2] {
    let Some((s, a, b)) = one_silent(range) else {
        return p;
    };
    let (o, d) = (
        sensors[a],
        [sensors[b][0] - sensors[a][0], sensors[b][1] - sensors[a][1]],
    );
    let len2 = d[0] * d[0] + d[1] * d[1];
    if len2 <= f64::MIN_POSITIVE {
        return p;
    }
    let t = ((p[0] - o[0]) * d[0] + (p[1] - o[1]) * d[1]) / len2;
    let mirror = [0, 1].map(|j| (2.0 * (o[j] + t * d[j]) - p[j]).clamp(-BOUND_MM, BOUND_MM));
    let dist2 = |q: [f64; 2]| {
        let (x, y) = (q[0] - sensors[s][0], q[1] - sensors[s][1]);
        x * x + y * y
    };
    if dist2(mirror) > dist2(p) { mirror } else { p }
}

#[cfg(test)]
mod tests {
    use super::*;
    // Sensors at (3, 0), (0, −3), (−3, 0) over a 12 × 12 mm pad (centres at x, y ∈ {−4, 0, 4}).
    use crate::score::tests::hand_pad;

    fn at(p: [f64; 2], model: &Ranging, pressure: [f32; 3]) -> ArrivalEvent {
        let s = [[3.0, 0.0], [0.0, -3.0], [-3.0, 0.0]];
        ArrivalEvent {
            pressure_pa: pressure,
            arrival_us: core::array::from_fn(|k| {
                let r = libm::sqrt((p[0] - s[k][0]).powi(2) + (p[1] - s[k][1]).powi(2));
                let t =
                    model.delay_us + model.us_per_mm * r + model.lag_us * model.lag(pressure[k]);
                Some(t.round() as u32)
            }),
        }
    }

    #[test]
    fn exact_ranges_give_the_point_and_its_area() {
        // a = 1 ms, b = 1 ms/mm, no lag. A press at (4, 0) (area 5's centre): r = 1, 5, 7 mm,
        // times 2, 6, 8 ms. The scores are −|p − centre|²: area 5 ≈ 0, area 4 ≈ −16,
        // area 2 (4, 4) ≈ −16, area 0 (−4, 4) ≈ −80.
        let m = Ranging::new(1000.0, 1000.0, 0.0, 0.0).unwrap();
        let e = ArrivalEvent {
            pressure_pa: [1.0; 3],
            arrival_us: [Some(2000), Some(6000), Some(8000)],
        };
        let p = m.position_mm(&hand_pad(), &e).unwrap();
        assert!((p[0] - 4.0).abs() < 1e-3 && p[1].abs() < 1e-3, "{p:?}");
        let s = m.scores(&hand_pad(), &e).unwrap();
        assert_eq!(s.argmax(), 5);
        assert!(s.values()[5] > -1e-5);
        assert!((s.values()[4] + 16.0).abs() < 1e-2);
        assert!((s.values()[0] + 80.0).abs() < 1e-1);
    }

    #[test]
    fn the_lag_of_a_weak_rise_is_removed() {
        // θ = 50 Pa; sensor 1's 100 Pa rise crosses ln 2 time constants late (c = 20 ms). With
        // the lag removed the press at (1.5, 1.5) mm (area 4, off-centre) is found again.
        let m = Ranging::new(2000.0, 2500.0, 20_000.0, 50.0).unwrap();
        let e = at([1.5, 1.5], &m, [100.0, 5000.0, 5000.0]);
        let p = m.position_mm(&hand_pad(), &e).unwrap();
        assert!(
            (p[0] - 1.5).abs() < 0.01 && (p[1] - 1.5).abs() < 0.01,
            "{p:?}"
        );
        assert_eq!(m.scores(&hand_pad(), &e).unwrap().argmax(), 4);
        // Ignoring the lag (c = 0) reads sensor 1 as 5.5 mm farther: the point is lost.
        let blind = Ranging::new(2000.0, 2500.0, 0.0, 50.0).unwrap();
        let q = blind.position_mm(&hand_pad(), &e).unwrap();
        assert!((q[0] - 1.5).hypot(q[1] - 1.5) > 1.0, "{q:?}");
    }

    #[test]
    fn with_one_silent_sensor_the_crossing_away_from_it_is_taken() {
        // Sensors (3, 0), (0, −3), (−3, 0). A press at (1, 2): sensor 2 (bottom) stays silent;
        // sensors 1 and 3 give ranges √8 and √20, whose circles also cross at (1, −2), the
        // mirror image across y = 0 — the line through the pad centre, where a search started
        // at the centre stalls. Silent sensor 2 is 5.1 mm from (1, 2) and 1.4 mm from (1, −2):
        // the far one is the answer.
        let m = Ranging::new(0.0, 1000.0, 0.0, 30.0).unwrap();
        let mut e = at([1.0, 2.0], &m, [5000.0; 3]);
        e.arrival_us[1] = None;
        let p = m.position_mm(&hand_pad(), &e).unwrap();
        assert!(
            (p[0] - 1.0).abs() < 1e-2 && (p[1] - 2.0).abs() < 1e-2,
            "{p:?}"
        );
        // The mirror press's ranges are the same, so with sensor 2 silent the answer is the
        // same far crossing (a press at (1, −2) silencing sensor 2, 1.4 mm away, would be odd).
        let mut below = at([1.0, -2.0], &m, [5000.0; 3]);
        below.arrival_us[1] = None;
        let q = m.position_mm(&hand_pad(), &below).unwrap();
        assert!(
            (q[0] - 1.0).abs() < 1e-2 && (q[1] - 2.0).abs() < 1e-2,
            "{q:?}"
        );
    }

    #[test]
    fn missing_single_equal_and_no_arrivals_are_defined() {
        let m = Ranging::new(0.0, 1000.0, 0.0, 30.0).unwrap();
        // Only sensor 3 (−3, 0), range 1 mm: the circle's point nearest the start (0, 0),
        // (−2, 0).
        let only3 = ArrivalEvent {
            pressure_pa: [0.0, 0.0, 100.0],
            arrival_us: [None, None, Some(1000)],
        };
        let p = m.position_mm(&hand_pad(), &only3).unwrap();
        assert!((p[0] + 2.0).abs() < 1e-2 && p[1].abs() < 1e-2, "{p:?}");
        // Equal times: the point equidistant from all three sensors, (0, 0), area 4.
        let equal = ArrivalEvent {
            pressure_pa: [100.0; 3],
            arrival_us: [Some(3000); 3],
        };
        assert_eq!(m.scores(&hand_pad(), &equal).unwrap().argmax(), 4);
        // Zero times: negative ranges after a positive delay; still finite.
        let late = Ranging::new(5000.0, 1000.0, 0.0, 30.0).unwrap();
        let zero = ArrivalEvent {
            pressure_pa: [100.0; 3],
            arrival_us: [Some(0); 3],
        };
        let s = late.scores(&hand_pad(), &zero).unwrap();
        assert!(s.values().iter().all(|v| v.is_finite()));
        let none = ArrivalEvent {
            pressure_pa: [0.0; 3],
            arrival_us: [None; 3],
        };
        assert_eq!(m.scores(&hand_pad(), &none), Err(AotError::NoArrival));
        let inf = ArrivalEvent {
            pressure_pa: [0.0, f32::INFINITY, 0.0],
            arrival_us: [Some(0); 3],
        };
        assert_eq!(
            m.scores(&hand_pad(), &inf),
            Err(AotError::NonFinitePressure { sensor: 1 })
        );
    }

    #[test]
    fn fit_recovers_the_model_that_made_the_times() {
        // Times made by a = 3 ms, b = 2.5 ms/mm, c = 20 ms, θ = 30 Pa at known points.
        let truth = Ranging::new(3000.0, 2500.0, 20_000.0, 30.0).unwrap();
        let s = [[3.0f64, 0.0], [0.0, -3.0], [-3.0, 0.0]];
        let mut fit = RangingFit::new(30.0);
        for i in 0..30u32 {
            let p = [f64::from(i % 6) - 2.5, f64::from(i % 5) - 2.0];
            let pressure = [40.0 + 9.0 * i as f32, 400.0, 35.0 + (i % 4) as f32 * 60.0];
            let e = at(p, &truth, pressure);
            let d = core::array::from_fn(|k| {
                libm::sqrt((p[0] - s[k][0]).powi(2) + (p[1] - s[k][1]).powi(2)) as f32
            });
            fit.push(&e, d);
        }
        let m = fit.finish().unwrap();
        assert_eq!(fit.taps(), 30);
        assert!((m.delay_us() - 3000.0).abs() < 5.0, "{m:?}");
        assert!((m.us_per_mm() - 2500.0).abs() < 2.0, "{m:?}");
        assert!((m.lag_us() - 20_000.0).abs() < 10.0, "{m:?}");
        assert_eq!(RangingFit::new(30.0).finish(), None);
    }
}
