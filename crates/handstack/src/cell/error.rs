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
    /// A device could not be opened (what `handstack run` says of it).
    #[error(transparent)]
    Open(Box<crate::RunError>),
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
    pub(crate) fn device(device: &'static str, e: impl core::fmt::Debug) -> CellError {
        CellError::Device {
            device,
            reason: format!("{e:?}"),
        }
    }
}

impl From<crate::RunError> for CellError {
    fn from(e: crate::RunError) -> CellError {
        CellError::Open(Box::new(e))
    }
}

impl From<crate::scene::SceneError> for CellError {
    fn from(e: crate::scene::SceneError) -> CellError {
        CellError::Scene(Box::new(e))
    }
}
