//! The simulator's one error type.

/// Why a simulation could not go on.
#[derive(Debug, thiserror::Error)]
pub enum SimError {
    /// A configuration value is outside what the model accepts.
    #[error("invalid {field}: {reason}")]
    Config {
        /// The offending field, as named in the scene file.
        field: &'static str,
        /// What is allowed.
        reason: String,
    },
    /// A scene file is not valid TOML or does not match the scene schema.
    #[error("scene file: {0}")]
    Scene(#[from] toml::de::Error),
    /// A chip driver reported an error while the simulator read it.
    #[error("{model}: driver error: {detail}")]
    Driver {
        /// The model whose chip failed.
        model: &'static str,
        /// The driver's error, formatted.
        detail: String,
    },
}

impl SimError {
    /// A [`SimError::Config`] for `field`.
    pub fn config(field: &'static str, reason: impl Into<String>) -> Self {
        SimError::Config {
            field,
            reason: reason.into(),
        }
    }
}
