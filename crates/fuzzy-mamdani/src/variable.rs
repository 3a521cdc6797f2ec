//! Linguistic variables: a universe (range) and its named terms.

use alloc::string::String;
use alloc::vec::Vec;

use crate::{Defuzzifier, Mf, SNorm};

/// A named membership function of a variable, e.g. `NH` or `cheap`.
#[derive(Debug, Clone, PartialEq)]
pub struct Term<T> {
    /// The term's name, unique within its variable.
    pub name: String,
    /// Its shape.
    pub mf: Mf<T>,
}

/// What an input outside its universe `[min, max]` does.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum OutOfRange {
    /// Saturate to the nearest bound (MATLAB's behaviour; the safe choice for control, and what
    /// makes ±∞ usable).
    #[default]
    Clamp,
    /// Evaluate the membership functions at the value as it is (fuzzylite's behaviour).
    Evaluate,
    /// Refuse with [`crate::EvalError::OutOfRange`].
    Error,
}

/// An input variable.
#[derive(Debug, Clone, PartialEq)]
pub struct InputVariable<T> {
    /// Name, unique among inputs and outputs.
    pub name: String,
    /// Lower bound of the universe.
    pub min: T,
    /// Upper bound of the universe.
    pub max: T,
    /// The terms, in declaration order.
    pub terms: Vec<Term<T>>,
    /// The policy for values outside `[min, max]`.
    pub out_of_range: OutOfRange,
}

/// An output variable and how its fuzzy set becomes a crisp value.
#[derive(Debug, Clone, PartialEq)]
pub struct OutputVariable<T> {
    /// Name, unique among inputs and outputs.
    pub name: String,
    /// Lower bound of the universe (the integration domain of the integral defuzzifiers).
    pub min: T,
    /// Upper bound of the universe.
    pub max: T,
    /// The terms, in declaration order.
    pub terms: Vec<Term<T>>,
    /// How the implied terms of all rules combine.
    pub aggregation: SNorm,
    /// How the aggregated set becomes one number.
    pub defuzzifier: Defuzzifier,
    /// The value when no rule fires (zero area or zero total weight); `None` makes that an
    /// [`crate::EvalError::NoRuleFired`].
    pub default: Option<T>,
}
