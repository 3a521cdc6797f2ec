//! The exact path: the aggregated set of piecewise-linear terms, walked piece by piece.
//!
//! Each implied term `I(w, μ(x))` is linear between the term's break points and, for min
//! implication, the points where μ crosses the clip level `w`. Between consecutive points of the
//! union of those break points every implied term is linear, so the aggregate is the sum of lines
//! (sum aggregation) or their upper envelope (max aggregation), itself found in closed form.

use alloc::vec::Vec;

use crate::{Mf, Real, SNorm, TNorm};

/// One implied consequent term: `term` of the output, its complement if `negated`, strength `w`,
/// implied by its rule block's `imp`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Act<T> {
    pub(crate) term: u32,
    pub(crate) negated: bool,
    pub(crate) w: T,
    pub(crate) imp: TNorm,
}

/// How many break points one activation contributes at most: 4 shape points + 2 clip points.
pub(crate) const POINTS_PER_ACT: usize = 6;

fn implied<T: Real>(mf: &Mf<T>, a: &Act<T>, x: T) -> T {
    let m = mf.membership(x);
    a.imp.apply(a.w, if a.negated { T::one() - m } else { m })
}

/// Calls `visit(u0, y0, u1, y1)` for each linear piece of the aggregated set over `[min, max]`,
/// left to right, in the universe's own frame `u = (x − centre) / half-span` ∈ [−1, 1] ([`Frame`]):
/// the moments and areas then stay far from overflow whatever the universe's size. `points` and
/// `lines` are scratch with enough capacity (no allocation).
#[allow(clippy::too_many_arguments)] // internal: every argument is a distinct piece of state
pub(crate) fn for_each_piece<T: Real>(
    acts: &[Act<T>],
    mfs: &[Mf<T>],
    aggregation: SNorm,
    (min, max): (T, T),
    points: &mut Vec<T>,
    lines: &mut Vec<(T, T)>,
    visit: &mut dyn FnMut(T, T, T, T),
) {
    points.clear();
    points.push(min);
    points.push(max);
    for a in acts {
        let Some(mf) = mfs.get(a.term as usize) else {
            continue;
        };
        if let Some((p, n)) = mf.linear_breakpoints() {
            points.extend(p[..n].iter().copied().filter(|x| *x > min && *x < max));
        }
        if a.imp == TNorm::Minimum {
            let level = if a.negated { T::one() - a.w } else { a.w };
            let (p, n) = mf.level_crossings(level);
            points.extend(p[..n].iter().copied().filter(|x| *x > min && *x < max));
        }
    }
    points.sort_unstable_by(|a, b| a.partial_cmp(b).unwrap_or(core::cmp::Ordering::Equal));
    points.dedup();
    let frame = Frame::new(min, max);
    for p in points.iter_mut() {
        *p = frame.u(*p);
    }

    let quarter = T::of(0.25);
    let (k1, k3) = (T::of(1.5), T::of(0.5));
    for seg in points.windows(2) {
        let (x0, x1) = (seg[0], seg[1]);
        let h = x1 - x0;
        if !(h > T::zero()) {
            continue;
        }
        // Sample strictly inside and extrapolate to the ends: a shoulder (a == b) jumps at its
        // break point, and only the one-sided limit belongs to this piece.
        let (q1, q3) = (frame.x(x0 + quarter * h), frame.x(x1 - quarter * h));
        lines.clear();
        for a in acts {
            let Some(mf) = mfs.get(a.term as usize) else {
                continue;
            };
            let (v1, v3) = (implied(mf, a, q1), implied(mf, a, q3));
            let y0 = (k1 * v1 - k3 * v3).max(T::zero());
            let y1 = (k1 * v3 - k3 * v1).max(T::zero());
            if y0 > T::zero() || y1 > T::zero() {
                lines.push((y0, y1));
            }
        }
        if aggregation == SNorm::UnboundedSum {
            let (y0, y1) = lines
                .iter()
                .fold((T::zero(), T::zero()), |s, l| (s.0 + l.0, s.1 + l.1));
            visit(x0, y0, x1, y1);
        } else {
            upper_envelope(lines, x0, x1, visit);
        }
    }
}

/// A universe's frame: its centre and half-span, both finite for any finite `[min, max]`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Frame<T> {
    centre: T,
    half: T,
}

impl<T: Real> Frame<T> {
    pub(crate) fn new(min: T, max: T) -> Self {
        let h = T::of(0.5);
        Frame {
            centre: crate::mf::midpoint(min, max),
            half: max * h - min * h,
        }
    }
    /// The frame coordinate of `x` (in `[−1, 1]` inside the universe).
    pub(crate) fn u(&self, x: T) -> T {
        (x - self.centre) / self.half
    }
    /// The point at frame coordinate `u`.
    pub(crate) fn x(&self, u: T) -> T {
        self.centre + self.half * u
    }
}

/// The upper envelope of lines given by their values at `x0` and `x1` (and of 0).
fn upper_envelope<T: Real>(lines: &[(T, T)], x0: T, x1: T, visit: &mut dyn FnMut(T, T, T, T)) {
    let h = x1 - x0;
    let slope = |l: &(T, T)| l.1 - l.0;
    let at = |l: &(T, T), t: T| l.0 + slope(l) * t;
    // Start on the highest line at t = 0, the steeper one on a tie.
    let Some(mut cur) = (0..lines.len()).max_by(|&i, &j| {
        let (a, b) = (&lines[i], &lines[j]);
        (a.0, slope(a))
            .partial_cmp(&(b.0, slope(b)))
            .unwrap_or(core::cmp::Ordering::Equal)
    }) else {
        visit(x0, T::zero(), x1, T::zero());
        return;
    };
    let mut t = T::zero();
    // Each switch goes to a strictly steeper line, so there are at most `lines.len()` switches.
    for _ in 0..=lines.len() {
        let c = &lines[cur];
        let mut next: Option<(usize, T)> = None;
        for (j, l) in lines.iter().enumerate() {
            let ds = slope(l) - slope(c);
            if !(ds > T::zero()) {
                continue;
            }
            let tc = ((c.0 - l.0) / ds).max(t);
            let better = match next {
                None => true,
                Some((b, tb)) => tc < tb || (tc == tb && slope(l) > slope(&lines[b])),
            };
            if tc < T::one() && better {
                next = Some((j, tc));
            }
        }
        let t_end = next.map_or(T::one(), |n| n.1);
        if t_end > t {
            visit(x0 + t * h, at(c, t), x0 + t_end * h, at(c, t_end));
        }
        match next {
            Some((j, tc)) => {
                cur = j;
                t = tc;
            }
            None => return,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn envelope_of_two_crossing_lines_switches_at_the_crossing() {
        let mut pieces = Vec::new();
        upper_envelope(&[(1.0, 0.0), (0.0, 1.0f64)], 0.0, 2.0, &mut |a, b, c, d| {
            pieces.push((a, b, c, d))
        });
        assert_eq!(pieces, [(0.0, 1.0, 1.0, 0.5), (1.0, 0.5, 2.0, 1.0)]);
    }

    #[test]
    fn clipped_triangle_has_a_plateau_between_the_clip_points() {
        let mfs = [Mf::Triangle {
            a: 0.0,
            b: 1.0,
            c: 2.0f64,
        }];
        let acts = [Act {
            term: 0,
            negated: false,
            w: 0.5,
            imp: TNorm::Minimum,
        }];
        let (mut pts, mut lines) = (Vec::with_capacity(8), Vec::with_capacity(1));
        let mut pieces = Vec::new();
        for_each_piece(
            &acts,
            &mfs,
            SNorm::Maximum,
            (0.0, 2.0),
            &mut pts,
            &mut lines,
            &mut |a, b, c, d| pieces.push((a, b, c, d)),
        );
        assert_eq!(pieces.len(), 4);
        // Pieces come in the frame of [0, 2]: u = x − 1.
        assert_eq!(pieces[1], (-0.5, 0.5, 0.0, 0.5));
    }
}
