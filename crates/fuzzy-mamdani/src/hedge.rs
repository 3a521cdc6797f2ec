//! Hedges: modifiers of a membership degree (`very`, `somewhat`, `not`, …), fuzzylite's set.
//!
//! In a rule a proposition reads `input is h1 h2 … term`; the hedge nearest the term applies
//! first (`very not A` is `(1 − μ_A)²`). In a conclusion the hedges modify the rule's
//! activation degree instead (fuzzylite's `Consequent::modify`): `then y is not B` implies `B`
//! with `1 − w`.

use crate::Real;

/// One hedge, with fuzzylite's name and formula.
///
/// ```
/// use fuzzy_mamdani::Hedge;
/// assert_eq!(Hedge::Very.apply(0.5), 0.25);
/// assert_eq!(Hedge::Not.apply(0.25), 0.75);
/// assert_eq!(Hedge::Extremely.apply(0.25), 0.125);
/// assert_eq!(Hedge::from_name("somewhat"), Some(Hedge::Somewhat));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Hedge {
    /// `1 − x`.
    Not,
    /// `√(x/2)` for `x ≤ ½`, else `1 − √((1 − x)/2)`.
    Seldom,
    /// `√x`.
    Somewhat,
    /// `x²`.
    Very,
    /// `2x²` for `x ≤ ½`, else `1 − 2(1 − x)²`.
    Extremely,
    /// `1` whatever `x`: `input is any` holds fully, with no term.
    Any,
}

impl Hedge {
    /// Every hedge, in the order of their codes.
    pub const ALL: [Hedge; 6] = [
        Hedge::Not,
        Hedge::Seldom,
        Hedge::Somewhat,
        Hedge::Very,
        Hedge::Extremely,
        Hedge::Any,
    ];

    /// The hedge's name in rule text.
    pub fn name(self) -> &'static str {
        match self {
            Hedge::Not => "not",
            Hedge::Seldom => "seldom",
            Hedge::Somewhat => "somewhat",
            Hedge::Very => "very",
            Hedge::Extremely => "extremely",
            Hedge::Any => "any",
        }
    }

    /// The hedge called `name` in rule text.
    pub fn from_name(name: &str) -> Option<Hedge> {
        Hedge::ALL.into_iter().find(|h| h.name() == name)
    }

    /// The hedged degree. For `x` in `[0, 1]` the result is in `[0, 1]`.
    #[inline]
    pub fn apply<T: Real>(self, x: T) -> T {
        let one = T::one();
        let half = T::of(0.5);
        let two = one + one;
        match self {
            Hedge::Not => one - x,
            Hedge::Seldom if x <= half => (half * x).sqrt(),
            Hedge::Seldom => one - (half * (one - x)).sqrt(),
            Hedge::Somewhat => x.sqrt(),
            Hedge::Very => x * x,
            Hedge::Extremely if x <= half => two * x * x,
            Hedge::Extremely => one - two * (one - x) * (one - x),
            Hedge::Any => one,
        }
    }

    fn code(self) -> u32 {
        match self {
            Hedge::Not => 1,
            Hedge::Seldom => 2,
            Hedge::Somewhat => 3,
            Hedge::Very => 4,
            Hedge::Extremely => 5,
            Hedge::Any => 6,
        }
    }

    fn of_code(code: u32) -> Option<Hedge> {
        Hedge::ALL.get((code as usize).checked_sub(1)?).copied()
    }
}

/// The hedges of one proposition, as written left to right, at most [`Hedges::MAX`]; `Copy`
/// and allocation-free (packed into one word), so a compiled rule evaluates them in place.
///
/// ```
/// use fuzzy_mamdani::{Hedge, Hedges};
/// let h = Hedges::new(&[Hedge::Very, Hedge::Not]).expect("two hedges fit");
/// assert_eq!(h.apply(0.25), 0.5625); // very (not 0.25) = 0.75²
/// assert_eq!(h.iter().collect::<Vec<_>>(), [Hedge::Very, Hedge::Not]);
/// assert_eq!(Hedges::NONE.apply(0.3), 0.3);
/// ```
#[derive(Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct Hedges {
    // 3 bits per hedge, the rightmost (applied first) in the lowest bits; 0 ends the list.
    packed: u32,
}

impl Hedges {
    /// The most hedges one proposition takes.
    pub const MAX: usize = 10;
    /// No hedge.
    pub const NONE: Hedges = Hedges { packed: 0 };
    /// `not` alone (a complemented proposition).
    pub const NOT: Hedges = Hedges { packed: 1 };

    /// `hedges` as written left to right; `None` when there are more than [`Hedges::MAX`].
    pub fn new(hedges: &[Hedge]) -> Option<Hedges> {
        if hedges.len() > Self::MAX {
            return None;
        }
        let packed = hedges.iter().fold(0u32, |p, h| (p << 3) | h.code());
        Some(Hedges { packed })
    }

    /// Whether there is no hedge.
    pub fn is_empty(self) -> bool {
        self.packed == 0
    }

    /// How many hedges.
    pub fn len(self) -> usize {
        (32 - self.packed.leading_zeros()).div_ceil(3) as usize
    }

    /// The hedges left to right.
    pub fn iter(self) -> impl Iterator<Item = Hedge> {
        let n = self.len();
        (0..n).filter_map(move |k| Hedge::of_code((self.packed >> (3 * (n - 1 - k))) & 7))
    }

    /// The hedges applied to `x`, the rightmost first.
    #[inline]
    pub fn apply<T: Real>(self, mut x: T) -> T {
        let mut p = self.packed;
        while p != 0 {
            if let Some(h) = Hedge::of_code(p & 7) {
                x = h.apply(x);
            }
            p >>= 3;
        }
        x
    }

    /// Whether the rightmost hedge is [`Hedge::Any`] (the proposition then has no term).
    pub fn ends_with_any(self) -> bool {
        self.packed & 7 == Hedge::Any.code()
    }
}

impl core::fmt::Debug for Hedges {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_list().entries(self.iter()).finish()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use alloc::vec::Vec;

    #[test]
    fn hedges_meet_fuzzylite_at_the_knots_and_stay_in_the_unit_interval() {
        assert_eq!(Hedge::Seldom.apply(0.5), 0.5);
        assert_eq!(Hedge::Extremely.apply(0.5), 0.5);
        assert_eq!(Hedge::Seldom.apply(0.0), 0.0);
        assert_eq!(Hedge::Seldom.apply(1.0), 1.0);
        for h in Hedge::ALL {
            for k in 0..=100 {
                let y = h.apply(k as f64 / 100.0);
                assert!((0.0..=1.0).contains(&y), "{h:?}");
            }
        }
    }

    #[test]
    fn packing_round_trips_and_refuses_too_many() {
        let all = Hedge::ALL;
        let h = Hedges::new(&all).expect("six fit");
        assert_eq!(h.len(), 6);
        assert_eq!(h.iter().collect::<Vec<_>>(), all);
        assert!(h.ends_with_any());
        assert!(Hedges::new(&[Hedge::Very; 11]).is_none());
        let ten = Hedges::new(&[Hedge::Any; 10]).expect("ten fit");
        assert_eq!(ten.len(), 10);
        assert_eq!(Hedges::NOT.iter().collect::<Vec<_>>(), [Hedge::Not]);
        assert_eq!(Hedges::NONE.len(), 0);
    }
}
