//! The crate's errors: [`RunError`] for running a model (no allocation, `no_std`), and
//! [`NetError`] (feature `std`) for everything else — building, training, files — which also
//! carries every [`RunError`].

use thiserror::Error;

/// Why a model could not run on an input: what inference on a microcontroller can meet.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Error)]
#[non_exhaustive]
pub enum RunError {
    /// An input vector had the wrong number of values.
    #[error("input has {got} values, the model reads {expected}")]
    Shape {
        /// Values the model reads.
        expected: usize,
        /// Values given.
        got: usize,
    },
    /// An input value was NaN or infinite.
    #[error("input value {index} is not finite")]
    NonFinite {
        /// Position of the first non-finite value.
        index: usize,
    },
    /// A finite input far outside the training range overflowed the model: its normalisation
    /// or its outputs became NaN or infinite.
    #[error("model value {index} is not finite (input far outside the training range?)")]
    NonFiniteOutput {
        /// Position of the first non-finite value (normalised input or output).
        index: usize,
    },
    /// A contact decoder had no catalogue contact to choose (or only NaN likelihoods).
    #[error("the contact catalogue is empty")]
    EmptyCatalogue,
}

/// Why a model could not be built, trained, saved, loaded or run.
#[cfg(feature = "std")]
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum NetError {
    /// An input vector had the wrong number of values.
    #[error("input has {got} values, the model reads {expected}")]
    Shape {
        /// Values the model reads.
        expected: usize,
        /// Values given.
        got: usize,
    },
    /// An input value was NaN or infinite.
    #[error("input value {index} is not finite")]
    NonFinite {
        /// Position of the first non-finite value.
        index: usize,
    },
    /// A finite input far outside the training range overflowed the model: its normalisation
    /// or its outputs became NaN or infinite.
    #[error("model value {index} is not finite (input far outside the training range?)")]
    NonFiniteOutput {
        /// Position of the first non-finite value (normalised input or output).
        index: usize,
    },
    /// A weights file (or a built-in model) could not be used: the file, and why.
    #[error("{file}: {source}")]
    InFile {
        /// The file (a built-in model: its path inside the package).
        file: String,
        /// What was wrong with it.
        source: Box<NetError>,
    },
    /// A stored tensor holds a NaN or infinite value.
    #[error("tensor `{tensor}`: value {index} is not finite")]
    NonFiniteWeight {
        /// Tensor name.
        tensor: String,
        /// Position of the first non-finite value (row-major).
        index: usize,
    },
    /// A decoder had nothing to decode to (an empty contact catalogue).
    #[error("the contact catalogue is empty")]
    EmptyCatalogue,
    /// A safetensors file could not be parsed or written.
    #[error("safetensors: {0}")]
    SafeTensors(String),
    /// A tensor the model needs is missing from a weights file.
    #[error("weights file has no tensor `{0}`")]
    MissingTensor(String),
    /// No built-in model is trained for this oversampling ratio.
    #[error(
        "no built-in contact MLP for OSR {osr}; built in: OSR {}",
        list(supported)
    )]
    UnsupportedOsr {
        /// The ratio asked for.
        osr: u16,
        /// The ratios that have one.
        supported: &'static [u16],
    },
    /// A stored tensor has another shape or dtype than the model expects.
    #[error("tensor `{name}`: stored {stored}, model expects {expected}")]
    TensorMismatch {
        /// Tensor name.
        name: String,
        /// Shape (or dtype) in the file.
        stored: String,
        /// Shape (or dtype) the model has.
        expected: String,
    },
    /// A dataset file did not parse.
    #[error("dataset line {line}: {reason}")]
    Data {
        /// 1-based line number.
        line: usize,
        /// What was wrong.
        reason: String,
    },
    /// A training set or configuration cannot train (no samples, zero batch size…).
    #[error("training: {0}")]
    Training(String),
    /// A metrics file did not parse or write.
    #[error("metrics: {0}")]
    Metrics(String),
    /// The compute device failed (out of memory).
    #[error("device: {0}")]
    Device(String),
    /// Reading or writing a file failed.
    #[error("io: {0}")]
    Io(#[from] std::io::Error),
}

#[cfg(feature = "std")]
impl NetError {
    /// `self`, as met in `file`.
    pub fn in_file(self, file: impl core::fmt::Display) -> NetError {
        NetError::InFile {
            file: file.to_string(),
            source: Box::new(self),
        }
    }
}

#[cfg(feature = "std")]
impl From<RunError> for NetError {
    fn from(e: RunError) -> Self {
        match e {
            RunError::Shape { expected, got } => NetError::Shape { expected, got },
            RunError::NonFinite { index } => NetError::NonFinite { index },
            RunError::NonFiniteOutput { index } => NetError::NonFiniteOutput { index },
            RunError::EmptyCatalogue => NetError::EmptyCatalogue,
        }
    }
}

#[cfg(feature = "train")]
impl From<dfdx::tensor::CpuError> for NetError {
    fn from(e: dfdx::tensor::CpuError) -> Self {
        NetError::Device(format!("{e:?}"))
    }
}

#[cfg(feature = "std")]
impl From<safetensors::SafeTensorError> for NetError {
    fn from(e: safetensors::SafeTensorError) -> Self {
        NetError::SafeTensors(e.to_string())
    }
}

/// Checks that `input` has `expected` values, all finite.
pub fn check_input(input: &[f32], expected: usize) -> Result<(), RunError> {
    if input.len() != expected {
        return Err(RunError::Shape {
            expected,
            got: input.len(),
        });
    }
    match input.iter().position(|v| !v.is_finite()) {
        Some(index) => Err(RunError::NonFinite { index }),
        None => Ok(()),
    }
}

/// Checks that every model output is finite.
pub fn check_output(output: &[f32]) -> Result<(), RunError> {
    match output.iter().position(|v| !v.is_finite()) {
        Some(index) => Err(RunError::NonFiniteOutput { index }),
        None => Ok(()),
    }
}

/// `256, 512, 1024`.
#[cfg(feature = "std")]
fn list(values: &[u16]) -> String {
    values
        .iter()
        .map(u16::to_string)
        .collect::<Vec<_>>()
        .join(", ")
}
