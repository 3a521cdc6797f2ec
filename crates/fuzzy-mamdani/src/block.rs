//! Rule blocks: groups of rules with their own operators and activation method (fuzzylite's
//! `RuleBlock`), all concluding into the same outputs.

use alloc::string::String;
use core::ops::Range;

use crate::{Activation, SNorm, TNorm};

/// One block of an engine's rules: its operators, its activation method, and which of the
/// engine's rules ([`crate::Engine::rules`]) it holds.
///
/// Blocks are evaluated in order; every block's conclusions aggregate into the same outputs
/// with each output's aggregation, each implied by its own block's implication.
#[derive(Debug, Clone, PartialEq)]
pub struct RuleBlock<T> {
    /// The block's name.
    pub name: String,
    /// The T-norm of `and` in this block's rules.
    pub conjunction: TNorm,
    /// The S-norm of `or` in this block's rules.
    pub disjunction: SNorm,
    /// How this block's rules shape their conclusions.
    pub implication: TNorm,
    /// Which of this block's rules take part.
    pub activation: Activation<T>,
    /// This block's rules, as indices into [`crate::Engine::rules`].
    pub rules: Range<usize>,
}
