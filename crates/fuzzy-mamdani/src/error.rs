//! Errors of building and of evaluating an engine.

use alloc::string::String;

use crate::MfError;

/// Why an engine could not be built.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum BuildError {
    /// A variable's range is empty, reversed or not finite.
    #[error("variable `{variable}`: range must be finite with min < max")]
    BadRange {
        /// The variable's name.
        variable: String,
    },
    /// A term's membership function parameters are unusable.
    #[error("term `{term}` of `{variable}`: {source}")]
    BadTerm {
        /// The variable's name.
        variable: String,
        /// The term's name.
        term: String,
        /// What is wrong with the parameters.
        source: MfError,
    },
    /// A variable has no terms.
    #[error("variable `{variable}` has no terms")]
    NoTerms {
        /// The variable's name.
        variable: String,
    },
    /// Two variables, or two terms of one variable, share a name.
    #[error("duplicate name `{name}`")]
    DuplicateName {
        /// The repeated name.
        name: String,
    },
    /// A rule names a variable or term that does not exist. (Messages count rules from 1, as
    /// a person does; the field from 0, as the engine's rule list.)
    #[error("rule {}: unknown {what} `{name}`", rule + 1)]
    Unknown {
        /// The rule's index (0-based).
        rule: usize,
        /// "input" (an index out of range), "variable" (a name that is neither an input nor an
        /// output), "output", "term" or "hedge".
        what: &'static str,
        /// The unknown name (or index, printed).
        name: String,
    },
    /// A rule has no consequent, or a weight outside `[0, 1]`.
    #[error("rule {}: {reason}", rule + 1)]
    BadRule {
        /// The rule's index (0-based).
        rule: usize,
        /// What is wrong.
        reason: &'static str,
    },
    /// A rule's text could not be parsed.
    #[error("rule {}, column {column}: expected {reason} in `{text}`", rule + 1)]
    RuleSyntax {
        /// The rule's index (0-based).
        rule: usize,
        /// The rule text.
        text: String,
        /// 1-based column (in characters) of the word where parsing stopped.
        column: usize,
        /// What was expected there.
        reason: &'static str,
    },
    /// The defuzzifier cannot be used with this output variable.
    #[error("output `{output}`: {reason}")]
    Defuzzifier {
        /// The output's name.
        output: String,
        /// Why (e.g. the exact path needs piecewise-linear terms).
        reason: &'static str,
    },
    /// The activation threshold is outside `[0, 1)` or NaN, or an activation method's
    /// parameter is not finite.
    #[error("the activation threshold must be in [0, 1) and activation parameters finite")]
    BadThreshold,
    /// No rule can ever fire for this output (none concludes on it, or only with weight 0)
    /// and it has no default value: every evaluation would fail.
    #[error("output `{output}`: no rule can fire for it and it has no default value")]
    NeverAnswers {
        /// The output's name.
        output: String,
    },
    /// The engine has no inputs or no outputs.
    #[error("an engine needs at least one input and one output")]
    Empty,
}

/// Why one evaluation gave no output.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum EvalError {
    /// The number of inputs given differs from the engine's.
    #[error("expected {expected} inputs, got {got}")]
    InputCount {
        /// The engine's input count.
        expected: usize,
        /// How many were given.
        got: usize,
    },
    /// An input is NaN or infinite.
    #[error("input {input} is not finite")]
    NonFiniteInput {
        /// The input's index.
        input: usize,
    },
    /// An input is outside its universe and its policy is [`crate::OutOfRange::Error`].
    #[error("input {input} is outside its range")]
    OutOfRange {
        /// The input's index.
        input: usize,
    },
    /// No rule fired for an output that declares no default value.
    #[error("no rule fired for output {output} and it has no default value")]
    NoRuleFired {
        /// The output's index.
        output: usize,
    },
    /// A control surface was asked for more steps per axis than it takes.
    #[error("{steps} steps per axis asked for, at most {max}")]
    TooManySteps {
        /// The steps asked for.
        steps: usize,
        /// The most accepted (`MAX_SURFACE_STEPS`).
        max: usize,
    },
    /// The scratch space was made for a different engine.
    #[error("scratch was made for another engine")]
    ScratchMismatch,
}
