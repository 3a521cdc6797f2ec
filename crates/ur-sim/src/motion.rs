//! Trapezoidal velocity profiles: accelerate at `a`, cruise at `v`, decelerate at `a`; a
//! triangle when the distance is too short to reach `v`.

/// A rest-to-rest profile over `length` (metres for moveL, radians of the leading joint for
/// moveJ).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Trapezoid {
    length: f64,
    v_peak: f64,
    a: f64,
    t_acc: f64,
    t_flat: f64,
}

impl Trapezoid {
    /// A profile; `v` and `a` must be positive and finite (the caller checks).
    pub(crate) fn new(length: f64, v: f64, a: f64) -> Self {
        let length = length.max(0.0);
        // Triangle if the accel + decel ramps to v would overshoot the length.
        let v_peak = v.min((length * a).sqrt());
        let t_acc = if a > 0.0 { v_peak / a } else { 0.0 };
        let ramp = v_peak * t_acc; // distance of both ramps together
        let t_flat = if v_peak > 0.0 {
            (length - ramp).max(0.0) / v_peak
        } else {
            0.0
        };
        Self {
            length,
            v_peak,
            a,
            t_acc,
            t_flat,
        }
    }

    /// Total duration, s.
    pub(crate) fn duration_s(&self) -> f64 {
        2.0 * self.t_acc + self.t_flat
    }

    /// Distance covered and speed at time `t` (clamped to the profile).
    pub(crate) fn at(&self, t: f64) -> (f64, f64) {
        let t = t.clamp(0.0, self.duration_s());
        let (ta, tf) = (self.t_acc, self.t_flat);
        if t < ta {
            (0.5 * self.a * t * t, self.a * t)
        } else if t < ta + tf {
            (0.5 * self.v_peak * ta + self.v_peak * (t - ta), self.v_peak)
        } else {
            let left = self.duration_s() - t;
            (self.length - 0.5 * self.a * left * left, self.a * left)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn trapezoid_ends_exactly_at_rest() {
        let p = Trapezoid::new(0.2, 0.25, 1.2);
        let (s, v) = p.at(p.duration_s());
        assert_eq!(s, 0.2);
        assert_eq!(v, 0.0);
        // cruise at v: 0.2 m at 0.25 m/s plus one ramp time (0.25 / 1.2 s).
        assert!((p.duration_s() - (0.2 / 0.25 + 0.25 / 1.2)).abs() < 1e-12);
    }

    #[test]
    fn short_move_is_a_triangle() {
        let p = Trapezoid::new(0.001, 1.0, 1.0);
        let (_, v_mid) = p.at(p.duration_s() / 2.0);
        assert!((v_mid - 0.001_f64.sqrt()).abs() < 1e-12);
        let (s, _) = p.at(1e9);
        assert_eq!(s, 0.001);
    }

    #[test]
    fn zero_length_takes_no_time() {
        let p = Trapezoid::new(0.0, 1.0, 1.0);
        assert_eq!(p.duration_s(), 0.0);
        assert_eq!(p.at(0.5), (0.0, 0.0));
    }
}
