//! The Pareto front of (cost, quality) points: the settings no other setting beats on both.

use super::error::TradeError;

/// Which way a task's quality figure improves.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Better {
    /// Higher is better (accuracy, %).
    Higher,
    /// Lower is better (an error or a noise figure).
    Lower,
}

impl Better {
    /// Whether quality `a` is at least as good as `b`.
    fn at_least(self, a: f64, b: f64) -> bool {
        match self {
            Better::Higher => a >= b,
            Better::Lower => a <= b,
        }
    }
}

/// For each `(cost, quality)` point, whether it is on the Pareto front: no other point costs no
/// more *and* is no worse, while being strictly better on one of the two. Cost is always
/// lower-is-better; `better` says which way quality goes. Equal points do not dominate each
/// other, so ties are all on the front (or all off it).
///
/// Errors: [`TradeError::NotFinite`] naming the first point with a NaN or infinite coordinate
/// (a NaN compares false both ways and would silently sit on the front).
///
/// ```
/// use paper_experiments::trade::{Better, pareto_front};
/// // (µs, % correct): the 3 µs point is dominated by the 2 µs one.
/// let front = pareto_front(&[(1.0, 80.0), (2.0, 90.0), (3.0, 85.0)], Better::Higher)?;
/// assert_eq!(front, [true, true, false]);
/// # Ok::<(), paper_experiments::trade::TradeError>(())
/// ```
pub fn pareto_front(points: &[(f64, f64)], better: Better) -> Result<Vec<bool>, TradeError> {
    if let Some(index) = points
        .iter()
        .position(|(c, q)| !c.is_finite() || !q.is_finite())
    {
        return Err(TradeError::NotFinite { index });
    }
    Ok(points
        .iter()
        .map(|&(c, q)| {
            !points.iter().any(|&(c2, q2)| {
                let no_worse = c2 <= c && better.at_least(q2, q);
                let strictly = c2 < c || (q2 != q && better.at_least(q2, q));
                no_worse && strictly
            })
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dominated_points_are_off_the_front_either_way() {
        let pts = [(1.0, 5.0), (2.0, 3.0), (3.0, 4.0), (4.0, 1.0)];
        // Lower quality is better: (3, 4) is beaten by (2, 3).
        assert_eq!(
            pareto_front(&pts, Better::Lower).unwrap(),
            [true, true, false, true]
        );
        // Higher is better: only the cheapest (which is also the best) survives.
        assert_eq!(
            pareto_front(&pts, Better::Higher).unwrap(),
            [true, false, false, false]
        );
    }

    #[test]
    fn ties_do_not_dominate_each_other() {
        let pts = [(1.0, 2.0), (1.0, 2.0), (1.0, 1.0), (0.5, 2.0)];
        // Same cost, worse quality: (1, 1) goes; the equal pair both lose to (0.5, 2).
        assert_eq!(
            pareto_front(&pts, Better::Higher).unwrap(),
            [false, false, false, true]
        );
        let equal = [(1.0, 2.0), (1.0, 2.0)];
        assert_eq!(pareto_front(&equal, Better::Lower).unwrap(), [true, true]);
        // Equal cost, better quality dominates.
        assert_eq!(
            pareto_front(&[(1.0, 3.0), (1.0, 2.0)], Better::Lower).unwrap(),
            [false, true]
        );
    }

    #[test]
    fn a_single_point_and_none_are_fronts() {
        assert_eq!(pareto_front(&[(7.0, 0.0)], Better::Higher).unwrap(), [true]);
        assert!(pareto_front(&[], Better::Lower).unwrap().is_empty());
    }

    #[test]
    fn nan_and_infinity_are_rejected_by_index() {
        assert_eq!(
            pareto_front(&[(1.0, 1.0), (f64::NAN, 1.0)], Better::Higher),
            Err(TradeError::NotFinite { index: 1 })
        );
        assert_eq!(
            pareto_front(&[(1.0, f64::INFINITY)], Better::Lower),
            Err(TradeError::NotFinite { index: 0 })
        );
    }
}
