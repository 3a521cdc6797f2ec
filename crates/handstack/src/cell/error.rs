//! What ends a node or a cell run.

use hand_zenoh::NodeError;

/// Why a node or a cell stopped.
#[derive(Debug, thiserror::Error)]
pub enum CellError {
    /// A device failed (the node stopped; the arm was stopped first).
    #[error("{device}: {reason}")]
    Device {
        /// The device.
        device: &'static str,
        /// What it said.
        reason: String,
    },
    /// Zenoh, a message or a service call failed.
    #[error(transparent)]
    Node(#[from] NodeError),
    /// A node the run needs was not in the graph in time, or left it.
    #[error("{node}: {what}")]
    Graph {
        /// The node's namespace.
        node: String,
        /// What happened (not seen within N s; left after N taps, seen N ms after).
        what: String,
    },
    /// What `handstack run` would say: a device that cannot be opened, a fault or a stop that
    /// ended a loop (after the hand's end action).
    #[error(transparent)]
    Run(Box<crate::RunError>),
    /// The scene file is wrong.
    #[error(transparent)]
    Scene(Box<crate::scene::SceneError>),
    /// The cell file is wrong.
    #[error("{path}: {reason}")]
    CellFile {
        /// The file.
        path: String,
        /// What is wrong.
        reason: String,
    },
    /// A node ended on `error`, its device left as `left` says (`hand released …`).
    #[error("{error}; {left}")]
    Left {
        /// What ended it.
        error: Box<CellError>,
        /// What its device was left doing.
        left: String,
    },
    /// A node process could not be started or failed.
    #[error("node process `{node}`: {reason}")]
    Process {
        /// The node's namespace.
        node: String,
        /// What happened.
        reason: String,
    },
}

impl CellError {
    pub(crate) fn device(device: &'static str, e: impl core::fmt::Display) -> CellError {
        CellError::Device {
            device,
            reason: e.to_string(),
        }
    }

    /// The exit status a node or cell process ends with for this error: `handstack run`'s
    /// for a device or a loop ([`RunError::exit_code`](crate::RunError::exit_code)), 3 for a
    /// device that failed in a node, else 1.
    pub fn exit_code(&self) -> u8 {
        match self {
            CellError::Run(e) => e.exit_code(),
            CellError::Left { error, .. } => error.exit_code(),
            CellError::Device { .. } => crate::error::EXIT_FAULT,
            _ => crate::error::EXIT_NOT_STARTED,
        }
    }
}

impl From<crate::RunError> for CellError {
    fn from(e: crate::RunError) -> CellError {
        CellError::Run(Box::new(e))
    }
}

impl From<crate::scene::SceneError> for CellError {
    fn from(e: crate::scene::SceneError) -> CellError {
        CellError::Scene(Box::new(e))
    }
}
