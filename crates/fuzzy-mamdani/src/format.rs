//! What the `.fis` and `.fll` readers and writers share: their error type and engine editing.

use std::string::String;

use crate::BuildError;

/// Why a `.fis` / `.fll` file could not be read or written.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum FileError {
    /// The text is malformed here.
    #[error("line {line}, column {column}: {message}")]
    Syntax {
        /// 1-based line number.
        line: usize,
        /// 1-based column (in characters) where the malformed part starts.
        column: usize,
        /// What was wrong, or what was expected instead.
        message: String,
    },
    /// The text names a variable, term or hedge that does not exist.
    #[error("line {line}: unknown {what} `{name}`")]
    Unknown {
        /// 1-based line number.
        line: usize,
        /// `"variable"`, `"output"`, `"term"` or `"hedge"`.
        what: &'static str,
        /// The name as written.
        name: String,
    },
    /// A feature of the format that this crate does not implement (reading, with its line),
    /// or one the format cannot express (writing, no line).
    #[error("{}", unsupported_message(*line, feature))]
    Unsupported {
        /// The feature, named as the format names it.
        feature: String,
        /// 1-based line number of its first use, when reading.
        line: Option<usize>,
    },
    /// A rule needs an operator (`conjunction`, `disjunction`, `implication`, `aggregation`)
    /// that the file sets to `none`: fuzzylite could not evaluate it either.
    #[error("line {line}: {needed_by} needs the {operator} operator, which is `none`")]
    MissingOperator {
        /// 1-based line of the rule (or of the `none`).
        line: usize,
        /// Which operator.
        operator: &'static str,
        /// What needs it.
        needed_by: String,
    },
    /// The file parsed but describes an unusable engine.
    #[error("{0}")]
    Build(#[from] BuildError),
}

fn unsupported_message(line: Option<usize>, feature: &str) -> String {
    match line {
        Some(line) => std::format!("line {line}: not supported: {feature}"),
        None => std::format!("cannot express in this format: {feature}"),
    }
}

/// A syntax error at `line` whose column the caller fills in ([`at_column`]).
pub(crate) fn syntax(line: usize, message: impl Into<String>) -> FileError {
    FileError::Syntax {
        line,
        column: 0,
        message: message.into(),
    }
}

/// An unsupported feature met while reading `line`.
pub(crate) fn unsupported(line: usize, feature: impl Into<String>) -> FileError {
    FileError::Unsupported {
        feature: feature.into(),
        line: Some(line),
    }
}

/// Gives a syntax error without a column (0) the column `column`.
pub(crate) fn at_column(e: FileError, column: usize) -> FileError {
    match e {
        FileError::Syntax {
            line,
            column: 0,
            message,
        } => FileError::Syntax {
            line,
            column,
            message,
        },
        e => e,
    }
}

/// Gives a syntax error without a column the column where its line's text starts.
pub(crate) fn at_line_start(e: FileError, text: &str) -> FileError {
    let column = match &e {
        FileError::Syntax { line, .. } => text.lines().nth(line.saturating_sub(1)).map_or(1, |l| {
            l.chars().take_while(|c| c.is_whitespace()).count() + 1
        }),
        _ => 1,
    };
    at_column(e, column)
}

/// A rule's build error at `line`, its text starting at `column`: syntax with the column in
/// the line, unknown names as [`FileError::Unknown`].
pub(crate) fn rule_error(e: BuildError, line: usize, column: usize) -> FileError {
    match e {
        BuildError::RuleSyntax {
            column: c, reason, ..
        } => FileError::Syntax {
            line,
            column: column + c - 1,
            message: std::format!("expected {reason}"),
        },
        BuildError::Unknown { what, name, .. } => FileError::Unknown { line, what, name },
        e => FileError::Build(e),
    }
}

/// Parses every whitespace- (or comma-) separated number of `text`.
pub(crate) fn numbers(text: &str, line: usize) -> Result<std::vec::Vec<f64>, FileError> {
    text.split(|c: char| c.is_whitespace() || c == ',')
        .filter(|t| !t.is_empty())
        .map(|t| {
            t.parse::<f64>()
                .map_err(|_| syntax(line, std::format!("`{t}` is not a number")))
        })
        .collect()
}
