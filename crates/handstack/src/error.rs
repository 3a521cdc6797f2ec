//! Errors of a scene run: the scene file, opening a device, or a part of the stack failing.

use crate::scene::SceneError;

/// Why a scene could not run to its end.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum RunError {
    /// The scene file is bad.
    #[error(transparent)]
    Scene(#[from] SceneError),
    /// A device the scene names cannot be opened (a real port, bus or host).
    #[error("cannot open {device} at {path}: {reason}")]
    Open {
        /// Which part (`hand`, `sensors.fingertip`, …).
        device: &'static str,
        /// The port, bus or host named in the scene.
        path: String,
        /// The system's or the device's answer.
        reason: String,
    },
    /// A device stopped working during the run (after its loop went to its safe state).
    #[error("{device}: {reason}")]
    Device {
        /// Which part.
        device: &'static str,
        /// What happened.
        reason: String,
    },
}
