//! Eq. 3 of Kim et al. 2020, "Artificial Intelligence-Based Optimal Grasping Control", §3,
//! and the area scores built on it.
//!
//! `Arr_n = Σ_k (P_k / r_{n,k}) · (Σ_x t_x / t_k)`: each sensor's pressure, divided by its
//! distance to area `n`, weighted by how early it sensed the contact relative to the total.
//! The area with the largest `Arr_n` is the touched one.

use crate::geometry::{AREAS, Geometry, SENSORS};

/// What eq. 3 reads for one contact: the three pressures and when each sensor sensed it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ArrivalEvent {
    /// `P_k`, Pa, in the geometry's sensor order. Which pressure (absolute, rise above
    /// baseline, held, peak) is the caller's choice; eq. 3 weights whatever it is given.
    pub pressure_pa: [f32; SENSORS],
    /// `t_k`: microseconds from contact onset until sensor `k` sensed it, `None` if it never
    /// did.
    pub arrival_us: [Option<u32>; SENSORS],
}

/// Why eq. 3 gave no scores.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum AotError {
    /// No sensor sensed the contact: every `t_k` is missing.
    NoArrival,
    /// Pressure `sensor` is NaN or infinite.
    NonFinitePressure {
        /// The sensor, 0…2.
        sensor: usize,
    },
}

impl core::fmt::Display for AotError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            AotError::NoArrival => f.write_str("no sensor sensed the contact"),
            AotError::NonFinitePressure { sensor } => {
                write!(f, "pressure of sensor {sensor} is not finite")
            }
        }
    }
}

/// `Arr_n` for the nine areas, with the winner and a confidence.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Scores {
    values: [f64; AREAS],
}

impl Scores {
    /// Wraps precomputed scores (from eq. 3 or another rule) for [`Scores::argmax`] and
    /// [`Scores::confidence`]. NaNs lose every comparison.
    pub fn from_values(values: [f64; AREAS]) -> Scores {
        Scores { values }
    }

    /// `Arr_n` for every area, 0…8 row-major.
    pub fn values(&self) -> &[f64; AREAS] {
        &self.values
    }

    /// The area with the largest score; the lowest index wins a tie.
    pub fn argmax(&self) -> usize {
        self.top_two().0
    }

    /// How far the winner is ahead of the runner-up, normalised:
    /// `(s₁ − s₂) / (|s₁| + |s₂|)`, in `0.0..=1.0` — 0 for a tie, 1 when the runner-up is 0
    /// or of the opposite sign. Scale-free (eq. 3's scores scale with pressure and timing),
    /// parameter-free unlike a softmax's temperature.
    pub fn confidence(&self) -> f32 {
        let (best, second) = self.top_two();
        let (s1, s2) = (self.values[best], self.values[second]);
        let den = s1.abs() + s2.abs();
        let c = (s1 - s2) / den;
        if c.is_finite() {
            c.clamp(0.0, 1.0) as f32
        } else {
            0.0
        }
    }

    fn top_two(&self) -> (usize, usize) {
        let (mut best, mut second) = (0, 1);
        if self.values[1] > self.values[0] {
            (best, second) = (1, 0);
        }
        for n in 2..AREAS {
            if self.values[n] > self.values[best] {
                (best, second) = (n, best);
            } else if self.values[n] > self.values[second] {
                second = n;
            }
        }
        (best, second)
    }
}

/// Eq. 3 exactly as written, for all nine areas.
///
/// Defined at the edges:
/// - a sensor that never arrived (`t_k = None`) contributes no term and no `t_x` to the sum
///   (its ratio `Σt / t_k` has no value); with no sensor arrived the result is
///   [`AotError::NoArrival`];
/// - `t_k = 0` is read as 1 µs, the input's resolution (the sensor arrived within the first
///   tick), so `Σt / t_k` stays finite, at most 3 · 2³²;
/// - equal times give every ratio 3 (`Σt / t_k = 3t / t`): eq. 3 then weights pressure alone;
/// - `r_{n,k} = 0` cannot reach here: [`Geometry`] refuses it.
///
/// Every finite input gives finite scores (f64 holds `f32::MAX · (1 / r) · 3 · 2³²`).
pub fn eq3(geometry: &Geometry, event: &ArrivalEvent) -> Result<Scores, AotError> {
    let mut ratio = [0.0f64; SENSORS];
    let mut total_us: u64 = 0;
    let mut arrived = 0;
    for t in event.arrival_us.iter().flatten() {
        total_us += u64::from((*t).max(1));
        arrived += 1;
    }
    if arrived == 0 {
        return Err(AotError::NoArrival);
    }
    for (k, (r, t)) in ratio.iter_mut().zip(event.arrival_us).enumerate() {
        if !event.pressure_pa[k].is_finite() {
            return Err(AotError::NonFinitePressure { sensor: k });
        }
        if let Some(t) = t {
            *r = total_us as f64 / f64::from(t.max(1));
        }
    }
    let inv_r = geometry.inverse_distances();
    let values = core::array::from_fn(|n| {
        let term = |k: usize| f64::from(event.pressure_pa[k]) * inv_r[n][k] * ratio[k];
        sum3_sorted([term(0), term(1), term(2)])
    });
    Ok(Scores { values })
}

/// `a + b + c` in ascending order: the same bits whatever order the sensors come in, so that
/// renumbering the sensors cannot change a score or break a tie differently.
pub(crate) fn sum3_sorted([mut a, mut b, mut c]: [f64; 3]) -> f64 {
    if a > b {
        core::mem::swap(&mut a, &mut b);
    }
    if b > c {
        core::mem::swap(&mut b, &mut c);
    }
    if a > b {
        core::mem::swap(&mut a, &mut b);
    }
    (a + b) + c
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::geometry::AreaGrid;

    /// A pad whose distances are easy by hand: sensors at (3, 0), (0, −3), (−3, 0) mm over a
    /// 12 × 12 mm pad (area centres at x, y ∈ {−4, 0, 4}). Also used by `ranging.rs`.
    pub(crate) fn hand_pad() -> Geometry {
        let grid = AreaGrid {
            width_mm: 12.0,
            height_mm: 12.0,
        };
        Geometry::new([[3.0, 0.0], [0.0, -3.0], [-3.0, 0.0]], grid).unwrap()
    }

    #[test]
    fn eq3_by_hand_centre_area() {
        // Area 4 (centre, (0, 0)): r = 3, 3, 3 for every sensor.
        // P = (30, 60, 90) Pa, t = (1, 2, 3) ms → Σt = 6 ms, ratios 6, 3, 2.
        // Arr_5 (eq. 3) = 30/3·6 + 60/3·3 + 90/3·2 = 60 + 60 + 60 = 180.
        let e = ArrivalEvent {
            pressure_pa: [30.0, 60.0, 90.0],
            arrival_us: [Some(1000), Some(2000), Some(3000)],
        };
        let s = eq3(&hand_pad(), &e).unwrap();
        assert!((s.values()[4] - 180.0).abs() < 1e-9);
    }

    #[test]
    fn eq3_by_hand_corner_area() {
        // Area 5 (middle right, (4, 0)): r = 1 to sensor 1 (3, 0), 5 to sensor 2 (0, −3)
        // (a 3-4-5 triangle), 7 to sensor 3 (−3, 0).
        // P = (70, 50, 35), t = (2, 4, 4) ms → Σt = 10, ratios 5, 2.5, 2.5.
        // Arr_6 = 70/1·5 + 50/5·2.5 + 35/7·2.5 = 350 + 25 + 12.5 = 387.5.
        let e = ArrivalEvent {
            pressure_pa: [70.0, 50.0, 35.0],
            arrival_us: [Some(2000), Some(4000), Some(4000)],
        };
        let s = eq3(&hand_pad(), &e).unwrap();
        assert!((s.values()[5] - 387.5).abs() < 1e-9);
        assert_eq!(s.argmax(), 5);
    }

    #[test]
    fn never_arrived_sensor_drops_out_of_terms_and_time_sum() {
        // Only sensors 1 and 3 arrived, at 1 and 3 ms: Σt = 4, ratios 4 and 4/3.
        // Area 4: r = 3 each → 30/3·4 + 90/3·4/3 = 40 + 40 = 80 (sensor 2's 60 Pa ignored).
        let e = ArrivalEvent {
            pressure_pa: [30.0, 60.0, 90.0],
            arrival_us: [Some(1000), None, Some(3000)],
        };
        let s = eq3(&hand_pad(), &e).unwrap();
        assert!((s.values()[4] - 80.0).abs() < 1e-9);
    }

    #[test]
    fn no_arrival_and_non_finite_pressure_are_errors() {
        let none = ArrivalEvent {
            pressure_pa: [1.0; 3],
            arrival_us: [None; 3],
        };
        assert_eq!(eq3(&hand_pad(), &none), Err(AotError::NoArrival));
        let nan = ArrivalEvent {
            pressure_pa: [1.0, f32::NAN, 1.0],
            arrival_us: [Some(1); 3],
        };
        assert_eq!(
            eq3(&hand_pad(), &nan),
            Err(AotError::NonFinitePressure { sensor: 1 })
        );
    }

    #[test]
    fn zero_and_equal_times_are_finite() {
        // All equal (here all zero, read as 1 µs): every ratio is 3, so area 4 scores
        // 3 · (30 + 60 + 90) / 3 = 180.
        let e = ArrivalEvent {
            pressure_pa: [30.0, 60.0, 90.0],
            arrival_us: [Some(0); 3],
        };
        let s = eq3(&hand_pad(), &e).unwrap();
        assert!((s.values()[4] - 180.0).abs() < 1e-9);
        // One zero among late arrivals: a huge but finite ratio.
        let e = ArrivalEvent {
            pressure_pa: [f32::MAX, f32::MAX, f32::MAX],
            arrival_us: [Some(0), Some(u32::MAX), Some(u32::MAX)],
        };
        assert!(
            eq3(&hand_pad(), &e)
                .unwrap()
                .values()
                .iter()
                .all(|v| v.is_finite())
        );
    }

    #[test]
    fn confidence_is_the_normalised_margin() {
        let mut v = [0.0; AREAS];
        v[3] = 3.0;
        v[7] = 1.0;
        let s = Scores::from_values(v);
        assert_eq!(s.argmax(), 3);
        assert!((s.confidence() - 0.5).abs() < 1e-6);
        let tie = Scores::from_values([2.0; AREAS]);
        assert_eq!((tie.argmax(), tie.confidence()), (0, 0.0));
        let zeros = Scores::from_values([0.0; AREAS]);
        assert_eq!(zeros.confidence(), 0.0);
    }
}
