//! What the `.fis` and `.fll` readers and writers share: their error type and engine editing.

use std::string::String;

use crate::BuildError;

/// Why a `.fis` / `.fll` file could not be read or written.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum FileError {
    /// The text is malformed at this line.
    #[error("line {line}: {message}")]
    Syntax {
        /// 1-based line number.
        line: usize,
        /// What was wrong.
        message: String,
    },
    /// The file parsed but describes an unusable engine.
    #[error("{0}")]
    Build(#[from] BuildError),
    /// The engine uses something the format cannot express.
    #[error("cannot express in this format: {0}")]
    Unsupported(String),
}

pub(crate) fn syntax(line: usize, message: impl Into<String>) -> FileError {
    FileError::Syntax {
        line,
        message: message.into(),
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
