//! Membership functions: the shapes a linguistic term takes over its variable's universe.
//!
//! Parameters follow MATLAB's Fuzzy Logic Toolbox order (`trimf [a b c]`, `gaussmf [σ c]`, …) so
//! that a `.fis` file maps onto a variant field by field.

use alloc::boxed::Box;

use crate::Real;

/// A membership function μ(x) ∈ [0, 1].
///
/// ```
/// use fuzzy_mamdani::Mf;
/// let tri = Mf::Triangle { a: 0.0, b: 5.0, c: 10.0 };
/// assert_eq!(tri.membership(2.5), 0.5);
/// let g = Mf::Gaussian { sigma: 1.0, mean: 0.0 };
/// assert!((g.membership(1.0) - (-0.5f64).exp()).abs() < 1e-15);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub enum Mf<T> {
    /// Triangle with feet `a`, `c` and peak `b` (eq. 6 of the grasp paper; MATLAB `trimf`).
    Triangle {
        /// Left foot.
        a: T,
        /// Peak.
        b: T,
        /// Right foot.
        c: T,
    },
    /// Trapezoid with feet `a`, `d` and plateau `b..=c` (MATLAB `trapmf`).
    Trapezoid {
        /// Left foot.
        a: T,
        /// Plateau start.
        b: T,
        /// Plateau end.
        c: T,
        /// Right foot.
        d: T,
    },
    /// Gaussian `exp(-(x-mean)²/(2σ²))` (eq. 5 of the grasp paper; MATLAB `gaussmf [σ c]`).
    Gaussian {
        /// Standard deviation σ > 0.
        sigma: T,
        /// Centre.
        mean: T,
    },
    /// Two-sided Gaussian: left flank (σ1, c1), 1 between c1 and c2, right flank (σ2, c2)
    /// (MATLAB `gauss2mf`).
    Gaussian2 {
        /// Left standard deviation.
        sigma1: T,
        /// Left centre.
        mean1: T,
        /// Right standard deviation.
        sigma2: T,
        /// Right centre.
        mean2: T,
    },
    /// Generalized bell `1 / (1 + |(x-c)/a|^(2b))` (MATLAB `gbellmf [a b c]`).
    Bell {
        /// Half width (non-zero).
        a: T,
        /// Slope exponent.
        b: T,
        /// Centre.
        c: T,
    },
    /// Sigmoid `1 / (1 + exp(-a (x - c)))` (MATLAB `sigmf [a c]`).
    Sigmoid {
        /// Slope; negative opens to the left.
        a: T,
        /// Inflection point.
        c: T,
    },
    /// `|sigmoid(a1, c1) - sigmoid(a2, c2)|` (MATLAB `dsigmf`, fuzzylite `SigmoidDifference`).
    SigmoidDifference {
        /// First slope.
        a1: T,
        /// First inflection.
        c1: T,
        /// Second slope.
        a2: T,
        /// Second inflection.
        c2: T,
    },
    /// `sigmoid(a1, c1) · sigmoid(a2, c2)` (MATLAB `psigmf`, fuzzylite `SigmoidProduct`).
    SigmoidProduct {
        /// First slope.
        a1: T,
        /// First inflection.
        c1: T,
        /// Second slope.
        a2: T,
        /// Second inflection.
        c2: T,
    },
    /// S-shaped spline from 0 at `a` to 1 at `b` (MATLAB `smf`).
    S {
        /// Foot.
        a: T,
        /// Shoulder.
        b: T,
    },
    /// Z-shaped spline from 1 at `a` to 0 at `b` (MATLAB `zmf`).
    Z {
        /// Shoulder.
        a: T,
        /// Foot.
        b: T,
    },
    /// Π-shaped: `S(a, b) · Z(c, d)` (MATLAB `pimf`).
    Pi {
        /// Left foot.
        a: T,
        /// Left shoulder.
        b: T,
        /// Right shoulder.
        c: T,
        /// Right foot.
        d: T,
    },
    /// 1 at exactly `x`, 0 elsewhere: a crisp input term, or an output term for the averaging
    /// defuzzifiers.
    Singleton {
        /// The one point of support.
        x: T,
    },
    /// A linear ramp from 0 at `start` to 1 at `end`, flat beyond (fuzzylite `Ramp`); falls
    /// when `end < start`. `start ≠ end`.
    Ramp {
        /// Where μ = 0.
        start: T,
        /// Where μ = 1.
        end: T,
    },
    /// 1 on `[start, end]` (both ends included), 0 elsewhere (fuzzylite `Rectangle`).
    Rectangle {
        /// Left edge.
        start: T,
        /// Right edge, `≥ start`.
        end: T,
    },
    /// `exp(−|10 (x − center) / width|)` (fuzzylite `Spike`).
    Spike {
        /// Peak.
        center: T,
        /// Width (positive): μ = e⁻⁵ at `center ± width / 2`.
        width: T,
    },
    /// `½ (1 + cos(2π (x − center) / width))` on `[center − width/2, center + width/2]`, 0
    /// elsewhere (fuzzylite `Cosine`).
    Cosine {
        /// Peak.
        center: T,
        /// Support width (positive).
        width: T,
    },
    /// fuzzylite's `Concave`: rising `(e − i) / (2e − i − x)` below `end` when
    /// `inflection ≤ end` (½ at the inflection, 1 from `end` on), falling
    /// `(i − e) / (i − 2e + x)` above `end` otherwise.
    Concave {
        /// Where μ = ½.
        inflection: T,
        /// Where μ reaches 1.
        end: T,
    },
    /// A step: 1 for `x ≥ start` when `rising`, for `x ≤ start` otherwise (fuzzylite `Binary`
    /// with direction `+∞` / `−∞`).
    Binary {
        /// The step's position (μ = 1 there).
        start: T,
        /// Which side is 1.
        rising: bool,
    },
    /// Linear interpolation between points `(x, μ)` with ascending `x`, the end values
    /// beyond (fuzzylite `Discrete`). The one shape not `Copy`-sized: its points are boxed.
    Discrete {
        /// The points, `x` ascending, `μ` in `[0, 1]`; at least one.
        points: Box<[(T, T)]>,
    },
}

/// Why a membership function's parameters are unusable.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum MfError {
    /// A parameter is NaN or infinite.
    #[error("a parameter is not finite")]
    NotFinite,
    /// The break points of a triangle, trapezoid or Π are not in ascending order.
    #[error("break points are not in ascending order")]
    Unordered,
    /// A width (σ, bell half width) is zero or negative.
    #[error("a width parameter must be positive")]
    NonPositiveWidth,
    /// A discrete shape has no point.
    #[error("a discrete shape needs at least one point")]
    NoPoints,
    /// A discrete shape's membership value is outside `[0, 1]`.
    #[error("membership values must be in [0, 1]")]
    OutOfUnitInterval,
}

impl<T: Real> Mf<T> {
    /// The parameters in MATLAB order (none for [`Mf::Discrete`], whose points are its own).
    pub fn params(&self) -> ([T; 4], usize) {
        let z = T::zero();
        match *self {
            Mf::Discrete { .. } => ([z; 4], 0),
            Mf::Triangle { a, b, c } | Mf::Bell { a, b, c } => ([a, b, c, z], 3),
            Mf::Trapezoid { a, b, c, d } | Mf::Pi { a, b, c, d } => ([a, b, c, d], 4),
            Mf::Gaussian { sigma, mean } => ([sigma, mean, z, z], 2),
            Mf::Gaussian2 {
                sigma1,
                mean1,
                sigma2,
                mean2,
            } => ([sigma1, mean1, sigma2, mean2], 4),
            Mf::Sigmoid { a, c } | Mf::S { a, b: c } | Mf::Z { a, b: c } => ([a, c, z, z], 2),
            Mf::SigmoidDifference { a1, c1, a2, c2 } | Mf::SigmoidProduct { a1, c1, a2, c2 } => {
                ([a1, c1, a2, c2], 4)
            }
            Mf::Singleton { x } | Mf::Binary { start: x, .. } => ([x, z, z, z], 1),
            Mf::Ramp { start, end } | Mf::Rectangle { start, end } => ([start, end, z, z], 2),
            Mf::Spike { center, width } | Mf::Cosine { center, width } => {
                ([center, width, z, z], 2)
            }
            Mf::Concave { inflection, end } => ([inflection, end, z, z], 2),
        }
    }

    /// Checks the parameters: all finite, break points ascending, widths positive.
    ///
    /// ```
    /// use fuzzy_mamdani::{Mf, MfError};
    /// assert_eq!(Mf::Triangle { a: 1.0, b: 0.0, c: 2.0 }.validate(), Err(MfError::Unordered));
    /// assert_eq!(Mf::Gaussian { sigma: 0.0, mean: 0.0 }.validate(), Err(MfError::NonPositiveWidth));
    /// ```
    pub fn validate(&self) -> Result<(), MfError> {
        let (p, n) = self.params();
        if p[..n].iter().any(|v| !v.is_finite()) {
            return Err(MfError::NotFinite);
        }
        if let Mf::Discrete { points } = self {
            if points.is_empty() {
                return Err(MfError::NoPoints);
            }
            if points.iter().any(|(x, y)| !x.is_finite() || !y.is_finite()) {
                return Err(MfError::NotFinite);
            }
            if points.windows(2).any(|w| !(w[0].0 <= w[1].0)) {
                return Err(MfError::Unordered);
            }
            if points.iter().any(|p| p.1 < T::zero() || p.1 > T::one()) {
                return Err(MfError::OutOfUnitInterval);
            }
        }
        let ascending = |s: &[T]| s.windows(2).all(|w| w[0] <= w[1]);
        match *self {
            Mf::Triangle { a, b, c } if !ascending(&[a, b, c]) => Err(MfError::Unordered),
            Mf::Trapezoid { a, b, c, d } | Mf::Pi { a, b, c, d } if !ascending(&[a, b, c, d]) => {
                Err(MfError::Unordered)
            }
            Mf::Gaussian { sigma, .. } if sigma <= T::zero() => Err(MfError::NonPositiveWidth),
            Mf::Gaussian2 { sigma1, sigma2, .. } if sigma1 <= T::zero() || sigma2 <= T::zero() => {
                Err(MfError::NonPositiveWidth)
            }
            Mf::Bell { a, .. } if a == T::zero() => Err(MfError::NonPositiveWidth),
            Mf::Ramp { start, end } if start == end => Err(MfError::NonPositiveWidth),
            Mf::Rectangle { start, end } if start > end => Err(MfError::Unordered),
            Mf::Spike { width, .. } | Mf::Cosine { width, .. } if width <= T::zero() => {
                Err(MfError::NonPositiveWidth)
            }
            _ => Ok(()),
        }
    }

    /// μ(x). Total for validated parameters: every finite `x` gives a value in `[0, 1]`.
    pub fn membership(&self, x: T) -> T {
        let zero = T::zero();
        let one = T::one();
        match *self {
            Mf::Triangle { a, b, c } => {
                // Comparisons first, so degenerate shoulders (a == b, b == c) never divide by 0.
                if x < a || x > c {
                    zero
                } else if x == b {
                    one
                } else if x < b {
                    ratio(x, a, b, a)
                } else {
                    ratio(c, x, c, b)
                }
            }
            Mf::Trapezoid { a, b, c, d } => {
                if x < a || x > d {
                    zero
                } else if x >= b && x <= c {
                    one
                } else if x < b {
                    ratio(x, a, b, a)
                } else {
                    ratio(d, x, d, c)
                }
            }
            Mf::Gaussian { sigma, mean } => gauss(x, sigma, mean),
            Mf::Gaussian2 {
                sigma1,
                mean1,
                sigma2,
                mean2,
            } => {
                let left = if x < mean1 {
                    gauss(x, sigma1, mean1)
                } else {
                    one
                };
                let right = if x > mean2 {
                    gauss(x, sigma2, mean2)
                } else {
                    one
                };
                left * right
            }
            Mf::Bell { a, b, c } => one / (one + quotient(x, c, a).abs().powf(b + b)),
            Mf::Sigmoid { a, c } => sigmoid(x, a, c),
            Mf::SigmoidDifference { a1, c1, a2, c2 } => {
                (sigmoid(x, a1, c1) - sigmoid(x, a2, c2)).abs()
            }
            Mf::SigmoidProduct { a1, c1, a2, c2 } => sigmoid(x, a1, c1) * sigmoid(x, a2, c2),
            Mf::S { a, b } => s_shape(x, a, b),
            Mf::Z { a, b } => one - s_shape(x, a, b),
            Mf::Pi { a, b, c, d } => s_shape(x, a, b) * (one - s_shape(x, c, d)),
            Mf::Singleton { x: at } => {
                if x == at {
                    one
                } else {
                    zero
                }
            }
            Mf::Ramp { start, end } => {
                if start < end {
                    if x <= start {
                        zero
                    } else if x >= end {
                        one
                    } else {
                        ratio(x, start, end, start)
                    }
                } else if x >= start {
                    zero
                } else if x <= end {
                    one
                } else {
                    ratio(start, x, start, end)
                }
            }
            Mf::Rectangle { start, end } => {
                if x >= start && x <= end {
                    one
                } else {
                    zero
                }
            }
            Mf::Spike { center, width } => {
                let ten = T::of(10.0);
                let t = x - center;
                // fuzzylite's order where x − center is finite (replayed to the last bits).
                let z = if t.is_finite() {
                    ten / width * t
                } else {
                    ten * quotient(x, center, width)
                };
                (-z.abs()).exp()
            }
            Mf::Cosine { center, width } => {
                let two = one + one;
                let half = width / two;
                let pi = T::of(core::f64::consts::PI);
                if (x - center).is_finite() && (center + half).is_finite() {
                    // fuzzylite's order of operations (replayed to the last bits).
                    if x < center - half || x > center + half {
                        zero
                    } else {
                        (one + (two * pi / width * (x - center)).cos()) / two
                    }
                } else {
                    let t = quotient(x, center, width);
                    if !(t.abs() <= T::of(0.5)) {
                        zero
                    } else {
                        (one + (two * pi * t).cos()) / two
                    }
                }
            }
            Mf::Concave {
                inflection: i,
                end: e,
            } => {
                if i <= e && x < e {
                    concave(e, i, e + e - i - x, [e, i, e, x])
                } else if i >= e && x > e {
                    concave(i, e, i - e - e + x, [i, e, x, e])
                } else {
                    one
                }
            }
            Mf::Binary { start, rising } => {
                if (rising && x >= start) || (!rising && x <= start) {
                    one
                } else {
                    zero
                }
            }
            Mf::Discrete { ref points } => discrete(points, x),
        }
    }

    /// The break points of a piecewise-linear shape (triangle, trapezoid), `None` for curves.
    ///
    /// Between consecutive break points the function is linear; the exact defuzzifiers rely on it.
    pub fn linear_breakpoints(&self) -> Option<([T; 4], usize)> {
        match *self {
            Mf::Triangle { .. } | Mf::Trapezoid { .. } => Some(self.params()),
            _ => None,
        }
    }

    /// The points on the sloped edges of a piecewise-linear shape where μ equals `level`
    /// (`0 < level < 1`); empty for curves. Min implication clips a term exactly there.
    pub fn level_crossings(&self, level: T) -> ([T; 2], usize) {
        let (a, b, c, d) = match *self {
            Mf::Triangle { a, b, c } => (a, b, b, c),
            Mf::Trapezoid { a, b, c, d } => (a, b, c, d),
            _ => return ([T::zero(); 2], 0),
        };
        if !(level > T::zero() && level < T::one()) {
            return ([T::zero(); 2], 0);
        }
        let mut out = [T::zero(); 2];
        let mut n = 0;
        if b > a {
            out[n] = lerp(a, b, level);
            n += 1;
        }
        if d > c {
            out[n] = lerp(d, c, level);
            n += 1;
        }
        (out, n)
    }

    /// The natural centre of a symmetric or peaked shape (triangle peak, trapezoid plateau
    /// middle, Gaussian mean, …), `None` for monotone shapes (sigmoid, S, Z).
    ///
    /// The center-average defuzzifier uses it; see [`crate::Defuzzifier::CenterAverage`].
    pub fn center(&self) -> Option<T> {
        match *self {
            Mf::Triangle { b, .. } => Some(b),
            Mf::Trapezoid { b, c, .. } | Mf::Pi { b, c, .. } => Some(midpoint(b, c)),
            Mf::Gaussian { mean, .. } => Some(mean),
            Mf::Gaussian2 { mean1, mean2, .. } => Some(midpoint(mean1, mean2)),
            Mf::Bell { c, .. } => Some(c),
            Mf::Singleton { x } => Some(x),
            Mf::Rectangle { start, end } => Some(midpoint(start, end)),
            Mf::Spike { center, .. } | Mf::Cosine { center, .. } => Some(center),
            Mf::Sigmoid { .. }
            | Mf::SigmoidDifference { .. }
            | Mf::SigmoidProduct { .. }
            | Mf::S { .. }
            | Mf::Z { .. }
            | Mf::Ramp { .. }
            | Mf::Concave { .. }
            | Mf::Binary { .. }
            | Mf::Discrete { .. } => None,
        }
    }
}

/// numpy's `interp` (pyfuzzylite's `Discrete`): the end values outside, linear between.
fn discrete<T: Real>(points: &[(T, T)], x: T) -> T {
    let (Some(first), Some(last)) = (points.first(), points.last()) else {
        return T::zero();
    };
    if x.is_nan() {
        return x;
    }
    if x <= first.0 {
        return first.1;
    }
    if x >= last.0 {
        return last.1;
    }
    // The first point strictly right of x (x < last.0, so there is one).
    let k = points.partition_point(|p| p.0 <= x);
    let ((x0, y0), (x1, y1)) = (points[k - 1], points[k]);
    // numpy: slope · (x − x0) + y0, in that order where nothing overflows.
    if (x1 - x0).is_finite() && (x - x0).is_finite() {
        (y1 - y0) / (x1 - x0) * (x - x0) + y0
    } else {
        y0 + (y1 - y0) * ratio(x, x0, x1, x0)
    }
}

/// `(p − q) / (r − s)` for `|p − q| ≤ |r − s|` (a point inside a slope: so only the
/// denominator can overflow, and it depends on the parameters alone), also where it overflows
/// (the operands halved, exact for normal numbers); the textbook form otherwise, so ordinary
/// numbers round as it does.
#[inline]
pub(crate) fn ratio<T: Real>(p: T, q: T, r: T, s: T) -> T {
    let d = r - s;
    if d.is_finite() {
        (p - q) / d
    } else {
        let h = T::of(0.5);
        (p * h - q * h) / (r * h - s * h)
    }
}

/// `(x − c) / w`, also where `x − c` overflows.
#[inline]
fn quotient<T: Real>(x: T, c: T, w: T) -> T {
    let n = x - c;
    if n.is_finite() {
        n / w
    } else {
        let h = T::of(0.5);
        (x * h - c * h) / (w * h)
    }
}

/// fuzzylite's Concave `(p − q) / den`, where `den` is `(p − q) + (r − s)` written in
/// fuzzylite's order (`parts` = `[p, q, r, s]`), recomputed halved where it overflows.
#[inline]
fn concave<T: Real>(p: T, q: T, den: T, [_, _, r, s]: [T; 4]) -> T {
    let n = p - q;
    if n.is_finite() && den.is_finite() {
        n / den
    } else {
        let h = T::of(0.5);
        let n = p * h - q * h;
        n / (n + (r * h - s * h))
    }
}

/// `(a + b) / 2`, also where the sum overflows.
#[inline]
pub(crate) fn midpoint<T: Real>(a: T, b: T) -> T {
    let two = T::one() + T::one();
    let sum = a + b;
    if sum.is_finite() {
        sum / two
    } else {
        a / two + b / two
    }
}

/// `a + t (b − a)` for `t` in `[0, 1]`, also where `b − a` overflows.
#[inline]
pub(crate) fn lerp<T: Real>(a: T, b: T, t: T) -> T {
    let d = b - a;
    if d.is_finite() {
        a + t * d
    } else {
        a * (T::one() - t) + b * t
    }
}

fn gauss<T: Real>(x: T, sigma: T, mean: T) -> T {
    let t = quotient(x, mean, sigma);
    (-(t * t) / (T::one() + T::one())).exp()
}

fn sigmoid<T: Real>(x: T, a: T, c: T) -> T {
    // exp overflows to +inf far on the closed side; 1 / (1 + inf) is then exactly 0. A flat
    // sigmoid (a = 0) is ½ everywhere, even where x − c overflows (0 · ∞ would be NaN).
    if a == T::zero() {
        return T::of(0.5);
    }
    let t = x - c;
    let e = if t.is_finite() {
        -a * t
    } else {
        // Only the exponent's sign matters: its size is beyond any exp's range.
        -a.signum() * t
    };
    T::one() / (T::one() + e.exp())
}

/// MATLAB's `smf`: a quadratic spline from 0 at `a` to 1 at `b`; a step at the middle if a ≥ b.
fn s_shape<T: Real>(x: T, a: T, b: T) -> T {
    let two = T::one() + T::one();
    let mid = midpoint(a, b);
    if a >= b {
        return if x >= mid { T::one() } else { T::zero() };
    }
    if x <= a {
        T::zero()
    } else if x <= mid {
        let t = ratio(x, a, b, a);
        two * t * t
    } else if x <= b {
        let t = ratio(x, b, b, a);
        T::one() - two * t * t
    } else {
        T::one()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn degenerate_triangle_shoulders_are_one_at_the_peak() {
        // scikit-fuzzy's trimf [0, 5, 5]: a right shoulder.
        let t = Mf::Triangle {
            a: 0.0,
            b: 5.0,
            c: 5.0,
        };
        assert_eq!(t.membership(5.0), 1.0);
        assert_eq!(t.membership(2.5), 0.5);
        assert_eq!(t.membership(5.1), 0.0);
    }

    #[test]
    fn s_z_pi_meet_their_matlab_knots() {
        let s = Mf::S { a: 1.0, b: 3.0 };
        assert_eq!(s.membership(1.0), 0.0);
        assert_eq!(s.membership(2.0), 0.5);
        assert_eq!(s.membership(3.0), 1.0);
        let z = Mf::Z { a: 1.0, b: 3.0 };
        assert_eq!(z.membership(2.0), 0.5);
        assert_eq!(z.membership(0.0), 1.0);
        let p = Mf::Pi {
            a: 0.0,
            b: 1.0,
            c: 2.0,
            d: 3.0,
        };
        assert_eq!(p.membership(1.5), 1.0);
        assert_eq!(p.membership(3.5), 0.0);
    }

    #[test]
    fn level_crossings_clip_both_edges() {
        let t = Mf::Trapezoid {
            a: 0.0,
            b: 2.0,
            c: 4.0,
            d: 8.0,
        };
        let (p, n) = t.level_crossings(0.5);
        assert_eq!(&p[..n], &[1.0, 6.0]);
        assert_eq!(t.level_crossings(1.0).1, 0);
    }

    #[test]
    fn far_inputs_stay_in_unit_interval() {
        let shapes = [
            Mf::Sigmoid { a: 50.0, c: 0.0 },
            Mf::Bell {
                a: 1.0,
                b: 200.0,
                c: 0.0,
            },
            Mf::Gaussian {
                sigma: 1e-3,
                mean: 0.0,
            },
            Mf::SigmoidDifference {
                a1: 9.0,
                c1: -1.0,
                a2: 9.0,
                c2: 1.0,
            },
        ];
        for s in shapes {
            for x in [-1e300, -1.0, 0.0, 1.0, 1e300] {
                let m = s.membership(x);
                assert!((0.0..=1.0).contains(&m), "{s:?} at {x}: {m}");
            }
        }
    }
}
