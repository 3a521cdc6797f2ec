//! What can go wrong in a trade run.

use thiserror::Error;

/// A trade run's error.
#[derive(Debug, Error, PartialEq)]
pub enum TradeError {
    /// A point's cost or quality is NaN or infinite.
    #[error("trade point {index} has a NaN or infinite cost or quality")]
    NotFinite {
        /// Index of the point in the slice given.
        index: usize,
    },
    /// A model, dataset or metrics file could not be used.
    #[error("{what}: {detail}")]
    Input {
        /// What was being read or evaluated.
        what: String,
        /// The underlying error.
        detail: String,
    },
    /// Writing the report failed.
    #[error("writing {path}: {detail}")]
    Write {
        /// The file.
        path: String,
        /// The underlying error.
        detail: String,
    },
}

impl TradeError {
    /// An [`TradeError::Input`] from any displayable error.
    pub(crate) fn input(what: impl Into<String>, e: impl std::fmt::Display) -> Self {
        TradeError::Input {
            what: what.into(),
            detail: e.to_string(),
        }
    }
}
