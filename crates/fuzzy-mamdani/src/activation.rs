//! Activation methods: which rules of the block take part, and with what degree (fuzzylite's
//! `activation:`), applied to the rules' weighted strengths before they imply anything.

use alloc::vec::Vec;

use crate::Real;

/// How the rules' activation degrees (weighted strengths) decide which rules are triggered.
///
/// Follows pyfuzzylite 8: every comparison is exact; "fired" means a degree above 0.
///
/// ```
/// use fuzzy_mamdani::{Activation, Comparison};
/// let a: Activation<f64> = Activation::Highest { rules: 2 };
/// assert_eq!(a.name(), "Highest");
/// let t = Activation::Threshold { comparison: Comparison::GreaterOrEqual, value: 0.3 };
/// assert_eq!(t.name(), "Threshold");
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Activation<T> {
    /// Every rule (fuzzylite's default; MATLAB's only method).
    General,
    /// The first `rules` rules in order whose degree is above 0 and at least `threshold`.
    First {
        /// How many rules at most.
        rules: usize,
        /// The least degree.
        threshold: T,
    },
    /// The last `rules` rules (walking backwards) whose degree is above 0 and at least
    /// `threshold`.
    Last {
        /// How many rules at most.
        rules: usize,
        /// The least degree.
        threshold: T,
    },
    /// The `rules` rules with the highest degrees above 0 (on a tie the earlier rule).
    Highest {
        /// How many rules at most.
        rules: usize,
    },
    /// The `rules` rules with the lowest degrees above 0 (on a tie the earlier rule).
    Lowest {
        /// How many rules at most.
        rules: usize,
    },
    /// The rules with degrees above 0, each degree divided by their sum.
    Proportional,
    /// The rules whose degree compares to `value` as `comparison` says.
    Threshold {
        /// The comparison, degree on the left.
        comparison: Comparison,
        /// The value compared with.
        value: T,
    },
}

/// A comparison of a rule's degree with a value ([`Activation::Threshold`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Comparison {
    /// `<`
    Less,
    /// `<=`
    LessOrEqual,
    /// `==`
    Equal,
    /// `!=`
    NotEqual,
    /// `>=`
    GreaterOrEqual,
    /// `>`
    Greater,
}

impl Comparison {
    /// Every comparison with its operator as written in `.fll`.
    pub const ALL: [(Comparison, &'static str); 6] = [
        (Comparison::Less, "<"),
        (Comparison::LessOrEqual, "<="),
        (Comparison::Equal, "=="),
        (Comparison::NotEqual, "!="),
        (Comparison::GreaterOrEqual, ">="),
        (Comparison::Greater, ">"),
    ];

    /// `a <op> b`.
    pub fn holds<T: Real>(self, a: T, b: T) -> bool {
        match self {
            Comparison::Less => a < b,
            Comparison::LessOrEqual => a <= b,
            Comparison::Equal => a == b,
            Comparison::NotEqual => a != b,
            Comparison::GreaterOrEqual => a >= b,
            Comparison::Greater => a > b,
        }
    }

    /// The operator as written in `.fll`.
    pub fn symbol(self) -> &'static str {
        Comparison::ALL
            .iter()
            .find(|(c, _)| *c == self)
            .map_or("", |(_, s)| s)
    }
}

impl<T: Real> Activation<T> {
    /// Every method's fuzzylite class name, in declaration order.
    pub const NAMES: [&'static str; 7] = [
        "General",
        "First",
        "Last",
        "Highest",
        "Lowest",
        "Proportional",
        "Threshold",
    ];

    /// fuzzylite's class name.
    pub fn name(&self) -> &'static str {
        match self {
            Activation::General => "General",
            Activation::First { .. } => "First",
            Activation::Last { .. } => "Last",
            Activation::Highest { .. } => "Highest",
            Activation::Lowest { .. } => "Lowest",
            Activation::Proportional => "Proportional",
            Activation::Threshold { .. } => "Threshold",
        }
    }

    /// Whether a parameter is NaN or infinite.
    pub(crate) fn is_valid(&self) -> bool {
        match *self {
            Activation::First { threshold, .. } | Activation::Last { threshold, .. } => {
                threshold.is_finite()
            }
            Activation::Threshold { value, .. } => value.is_finite(),
            _ => true,
        }
    }

    /// How the method visits its block's rules when it triggers each as it goes:
    /// `Some(false)` in rule order (`General`, `First`, `Threshold`), `Some(true)` from the
    /// last rule (`Last`); `None` when it compares every rule's degree before triggering any
    /// (`Highest`, `Lowest`, `Proportional`). This decides which conclusions a chained
    /// engine's rule sees ([`crate::Expr::Output`]), as in pyfuzzylite's `activate` methods.
    pub(crate) fn rule_by_rule(&self) -> Option<bool> {
        match self {
            Activation::General | Activation::First { .. } | Activation::Threshold { .. } => {
                Some(false)
            }
            Activation::Last { .. } => Some(true),
            Activation::Highest { .. } | Activation::Lowest { .. } | Activation::Proportional => {
                None
            }
        }
    }

    /// For a rule-by-rule method ([`Self::rule_by_rule`]): whether the next rule visited, of
    /// degree `d`, is triggered; `taken` counts the rules triggered so far in the block.
    pub(crate) fn triggers(&self, d: T, taken: &mut usize) -> bool {
        let on = match *self {
            Activation::First { rules, threshold } | Activation::Last { rules, threshold } => {
                *taken < rules && d > T::zero() && d >= threshold
            }
            Activation::Threshold { comparison, value } => comparison.holds(d, value),
            _ => true,
        };
        *taken += usize::from(on);
        on
    }

    /// Applies the method to `degree` (one per rule, in rule order): a rule left out gets
    /// [`UNTRIGGERED`]'s NaN, which no hedge turns into a number and no threshold passes.
    /// `chosen` is scratch for the ranking methods (capacity: the rule count).
    pub(crate) fn apply(&self, degree: &mut [T], chosen: &mut Vec<u32>) {
        let off = untriggered::<T>();
        let zero = T::zero();
        match *self {
            Activation::General => {}
            Activation::First { .. } | Activation::Last { .. } | Activation::Threshold { .. } => {
                let mut taken = 0usize;
                let mut visit = |d: &mut T| {
                    if !self.triggers(*d, &mut taken) {
                        *d = off;
                    }
                };
                if self.rule_by_rule() == Some(true) {
                    degree.iter_mut().rev().for_each(&mut visit);
                } else {
                    degree.iter_mut().for_each(&mut visit);
                }
            }
            Activation::Highest { rules } | Activation::Lowest { rules } => {
                let highest = matches!(self, Activation::Highest { .. });
                chosen.clear();
                // `rules` passes of a selection: no allocation, and `rules` is small.
                for _ in 0..rules.min(degree.len()) {
                    let mut best: Option<(usize, T)> = None;
                    for (r, &d) in degree.iter().enumerate() {
                        if !(d > zero) || chosen.contains(&(r as u32)) {
                            continue;
                        }
                        let better = match best {
                            None => true,
                            Some((_, b)) if highest => d > b,
                            Some((_, b)) => d < b,
                        };
                        if better {
                            best = Some((r, d));
                        }
                    }
                    match best {
                        Some((r, _)) => chosen.push(r as u32),
                        None => break,
                    }
                }
                for (r, d) in degree.iter_mut().enumerate() {
                    if !chosen.contains(&(r as u32)) {
                        *d = off;
                    }
                }
            }
            Activation::Proportional => {
                let sum = degree
                    .iter()
                    .filter(|d| **d > zero)
                    .fold(zero, |s, &d| s + d);
                for d in degree.iter_mut() {
                    *d = if *d > zero { *d / sum } else { off };
                }
            }
        }
    }
}

/// The degree of a rule its block's activation method leaves out.
pub(crate) fn untriggered<T: Real>() -> T {
    T::nan()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn run(a: Activation<f64>, d: &[f64]) -> Vec<Option<f64>> {
        let mut d = d.to_vec();
        let mut chosen = Vec::with_capacity(d.len());
        a.apply(&mut d, &mut chosen);
        d.into_iter().map(|v| (!v.is_nan()).then_some(v)).collect()
    }

    #[test]
    fn each_method_picks_as_pyfuzzylite_does() {
        let d = [0.2, 0.0, 0.7, 0.7, 0.1];
        assert_eq!(
            run(
                Activation::First {
                    rules: 2,
                    threshold: 0.15
                },
                &d
            ),
            [Some(0.2), None, Some(0.7), None, None]
        );
        assert_eq!(
            run(
                Activation::Last {
                    rules: 2,
                    threshold: 0.0
                },
                &d
            ),
            [None, None, None, Some(0.7), Some(0.1)]
        );
        // A tie goes to the earlier rule.
        assert_eq!(
            run(Activation::Highest { rules: 1 }, &d),
            [None, None, Some(0.7), None, None]
        );
        assert_eq!(
            run(Activation::Lowest { rules: 2 }, &d),
            [Some(0.2), None, None, None, Some(0.1)]
        );
        let p = run(Activation::Proportional, &d);
        assert!((p[2].unwrap_or(0.0) - 0.7 / 1.7).abs() < 1e-15 && p[1].is_none());
        let t = Activation::Threshold {
            comparison: Comparison::Less,
            value: 0.2,
        };
        assert_eq!(run(t, &d), [None, Some(0.0), None, None, Some(0.1)]);
        assert_eq!(run(Activation::General, &d), d.map(Some));
        let nan = Activation::Threshold {
            comparison: Comparison::Equal,
            value: f64::NAN,
        };
        assert!(!nan.is_valid());
    }
}
