//! The pad-only half of the ranging scorer's position fix, computed once when a [`Geometry`]
//! is built instead of on every localisation: the sensors' canonical order, their positions in
//! that order, the linearised fix's coefficients, the pad centre and the area centres in f64.
//!
//! [`Geometry`]: crate::Geometry

use crate::geometry::{AREAS, SENSORS};

/// The position search stays within this many mm of the pad centre (far beyond any pad), so
/// absurd ranges still give finite scores.
pub(crate) const BOUND_MM: f64 = 1e4;

/// Geometry-only parts of [`crate::Ranging::position_mm`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Trilateration {
    /// Sensor indices sorted by position (x, then y, by `total_cmp`); `None` when two sensors
    /// share a position, where the order must also look at the inputs (see [`Self::order`]).
    order: Option<[usize; SENSORS]>,
    /// Sensor positions in canonical order, mm. Tied sensors have equal positions, so this is
    /// the same whichever of them comes first.
    pub(crate) sensors: [[f64; 2]; SENSORS],
    /// The linearised three-range fix, `None` for collinear sensors.
    pub(crate) linear: Option<LinearFix>,
    /// The mean of the area centres: the search's start with fewer than three ranges.
    pub(crate) centre: [f64; 2],
    /// The area centres in f64, as the scores use them.
    pub(crate) centres: [[f64; 2]; AREAS],
}

/// The linearised fix from three ranges in canonical order: `|p − s_k|² = ρ_k²` minus the same
/// for sensor 0 is linear in `p`, `2(s_k − s_0)·p = (|s_k|² − ρ_k²) − (|s_0|² − ρ_0²)`; solved by
/// least squares in the centred form `p = Σ_k m_k (q_k − q_0)`, `m_k = H⁻¹ a_k`,
/// `a_k = 2(s_k − s̄)`, `H = Σ a_k a_kᵀ` (`Σ_k m_k = 0`, so any reference `q_0` gives the same
/// fix). Everything but the ranges is geometry, so a fix is
/// `p = base − m_1 (ρ_1² − ρ_0²) − m_2 (ρ_2² − ρ_0²)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct LinearFix {
    m: [[f64; 2]; 2],
    base: [f64; 2],
}

impl LinearFix {
    /// The fix for three ranges in canonical order, clamped to [`BOUND_MM`]; `None` if it is
    /// not finite (ranges beyond f64's squares).
    #[inline]
    pub(crate) fn solve(&self, rho: [f64; SENSORS]) -> Option<[f64; 2]> {
        let r0 = rho[0] * rho[0];
        let d1 = rho[1] * rho[1] - r0;
        let d2 = rho[2] * rho[2] - r0;
        let p = [0, 1].map(|j| (self.base[j] - self.m[0][j] * d1) - self.m[1][j] * d2);
        (p[0].is_finite() && p[1].is_finite()).then(|| p.map(|v| v.clamp(-BOUND_MM, BOUND_MM)))
    }
}

impl Trilateration {
    /// Precomputes for sensors (any numbering) and area centres, all finite.
    pub(crate) fn new(
        sensors_mm: &[[f32; 2]; SENSORS],
        centres_mm: &[[f32; 2]; AREAS],
    ) -> Trilateration {
        let key = |k: usize| sensors_mm[k];
        let after = |i: usize, j: usize| {
            let (a, b) = (key(i), key(j));
            a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])).is_gt()
        };
        let sorted = sort3(after);
        let same = |i: usize, j: usize| !after(i, j) && !after(j, i);
        let distinct = !(same(sorted[0], sorted[1]) || same(sorted[1], sorted[2]));
        let sensors = sorted.map(|k| sensors_mm[k].map(f64::from));
        let centres = centres_mm.map(|c| c.map(f64::from));
        let centre = [0, 1].map(|j| centres.iter().map(|c| c[j]).sum::<f64>() / 9.0);
        Trilateration {
            order: distinct.then_some(sorted),
            sensors,
            linear: linear_fix(&sensors),
            centre,
            centres,
        }
    }

    /// The canonical order for these inputs: the precomputed one, or (two sensors at one
    /// position) by position, then arrival time, then pressure, so that the same sequence of
    /// (position, input) pairs comes out whatever numbering the sensors come in. Sensors equal
    /// in every key give identical terms, so their relative order cannot matter.
    #[inline]
    pub(crate) fn order(
        &self,
        sensors_mm: &[[f32; 2]; SENSORS],
        arrival_us: &[Option<u32>; SENSORS],
        pressure_pa: &[f32; SENSORS],
    ) -> [usize; SENSORS] {
        if let Some(o) = self.order {
            return o;
        }
        sort3(|i, j| {
            let (si, sj) = (sensors_mm[i], sensors_mm[j]);
            si[0]
                .total_cmp(&sj[0])
                .then(si[1].total_cmp(&sj[1]))
                .then(arrival_us[i].cmp(&arrival_us[j]))
                .then(pressure_pa[i].total_cmp(&pressure_pa[j]))
                .is_gt()
        })
    }
}

/// 0, 1, 2 sorted by a three-compare network under `after(i, j)` ("i goes after j").
fn sort3(after: impl Fn(usize, usize) -> bool) -> [usize; SENSORS] {
    let mut o = [0, 1, 2];
    if after(o[0], o[1]) {
        o.swap(0, 1);
    }
    if after(o[1], o[2]) {
        o.swap(1, 2);
    }
    if after(o[0], o[1]) {
        o.swap(0, 1);
    }
    o
}

/// `f(0) + f(1) + f(2)`, in that order.
fn sum3(f: impl Fn(usize) -> f64) -> f64 {
    (f(0) + f(1)) + f(2)
}

/// [`LinearFix`] for sensors in canonical order; `None` for collinear sensors (or a NaN).
fn linear_fix(sensors: &[[f64; 2]; SENSORS]) -> Option<LinearFix> {
    let sbar = [0, 1].map(|j| sum3(|k| sensors[k][j]) / 3.0);
    let a: [[f64; 2]; 3] =
        core::array::from_fn(|k| [0, 1].map(|j| 2.0 * (sensors[k][j] - sbar[j])));
    let (hxx, hxy, hyy) = (
        sum3(|k| a[k][0] * a[k][0]),
        sum3(|k| a[k][0] * a[k][1]),
        sum3(|k| a[k][1] * a[k][1]),
    );
    let det = hxx * hyy - hxy * hxy;
    // Collinear sensors (or a NaN) leave the fix undetermined.
    if det.is_nan() || det <= 1e-9 * (hxx * hyy) {
        return None;
    }
    let m: [[f64; 2]; 3] = core::array::from_fn(|k| {
        [
            (hyy * a[k][0] - hxy * a[k][1]) / det,
            (hxx * a[k][1] - hxy * a[k][0]) / det,
        ]
    });
    let norm2 = |k: usize| sensors[k][0] * sensors[k][0] + sensors[k][1] * sensors[k][1];
    let dn = [norm2(1) - norm2(0), norm2(2) - norm2(0)];
    let base = [0, 1].map(|j| m[1][j] * dn[0] + m[2][j] * dn[1]);
    let fix = LinearFix {
        m: [m[1], m[2]],
        base,
    };
    let finite = fix
        .m
        .iter()
        .chain([&fix.base])
        .flatten()
        .all(|v| v.is_finite());
    finite.then_some(fix)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::AreaGrid;

    /// The area centres of an 18 × 12 mm test pad.
    fn centres() -> [[f32; 2]; AREAS] {
        AreaGrid {
            width_mm: 18.0,
            height_mm: 12.0,
        }
        .centres_mm()
    }

    #[test]
    fn order_is_by_position_and_the_fix_inverts_exact_ranges() {
        let sensors = [[3.0, 0.0], [0.0, -3.0], [-3.0, 0.0]];
        let t = Trilateration::new(&sensors, &centres());
        // By x: (−3, 0), (0, −3), (3, 0).
        assert_eq!(t.order(&sensors, &[None; 3], &[0.0; 3]), [2, 1, 0]);
        assert_eq!(t.centre, [0.0, 0.0]);
        // A point at (1, 2): ranges √20, √26, √8 in canonical order.
        let p = [1.0f64, 2.0];
        let rho = t
            .sensors
            .map(|s| ((p[0] - s[0]).powi(2) + (p[1] - s[1]).powi(2)).sqrt());
        let q = t.linear.unwrap().solve(rho).unwrap();
        assert!(
            (q[0] - 1.0).abs() < 1e-12 && (q[1] - 2.0).abs() < 1e-12,
            "{q:?}"
        );
    }

    #[test]
    fn collinear_or_shared_positions_have_no_fix_and_an_input_order() {
        let line = [[0.0, 0.0], [1.0, 1.0], [2.0, 2.0]];
        assert_eq!(Trilateration::new(&line, &centres()).linear, None);
        let shared = [[1.0, 1.0], [0.0, 0.0], [1.0, 1.0]];
        let t = Trilateration::new(&shared, &centres());
        assert_eq!(t.linear, None);
        // Sensors 0 and 2 share (1, 1): the earlier arrival goes first.
        let arrivals = [Some(9), Some(1), Some(5)];
        assert_eq!(t.order(&shared, &arrivals, &[0.0; 3]), [1, 2, 0]);
        // Ranges far beyond the pad give a clamped, finite fix or none.
        let far = Trilateration::new(&[[3.0, 0.0], [0.0, -3.0], [-3.0, 0.0]], &centres());
        let q = far.linear.unwrap().solve([1e150, 0.0, 0.0]);
        assert!(q.is_none_or(|q| q.iter().all(|v| v.abs() <= BOUND_MM)));
    }
}
