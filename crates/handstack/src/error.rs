//! Errors of a scene run: the scene file, opening a device, or the run ending before its end
//! (a stop, a fault, a failed experiment), each with the exit status it gives.

use crate::scene::SceneError;
use crate::stop::StopReason;

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
    /// A device failed outside a control loop (a sensor read of a readout, a setting refused).
    #[error("{device}: {reason}")]
    Device {
        /// Which part.
        device: &'static str,
        /// What happened.
        reason: String,
    },
    /// The run ended before its end; the hand (if any) got its end action first.
    #[error("{what}")]
    Ended {
        /// How it ended.
        ending: Ending,
        /// What happened, when, and what the hand was left doing, in words.
        what: String,
    },
}

/// How a run that did not reach its end ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Ending {
    /// A signal or a stop request ended it.
    Stopped(StopReason),
    /// A device faulted (and the scene's recovery, if any, did not bring it back) or was lost.
    Fault,
    /// The experiment could not do what it is for (the loop never commanded; the fingertip
    /// never saw contact).
    Failed,
    /// A bug: the run's own code (or a part's) panicked; the hand got its end action first.
    Bug,
}

/// Exit status of a run that could not start: a bad scene, a device that cannot be opened.
pub const EXIT_NOT_STARTED: u8 = 1;
/// Exit status of a run a device fault ended.
pub const EXIT_FAULT: u8 = 3;
/// Exit status of a run whose experiment failed.
pub const EXIT_FAILED: u8 = 4;
/// Exit status of a run a bug ended: Rust's for a panic.
pub const EXIT_BUG: u8 = 101;

impl RunError {
    /// The exit status this error ends `handstack` with: 1 the run could not start (scene,
    /// opening), 3 a device fault ended it, 4 its experiment failed, 128 + n a signal n
    /// stopped it (130 for Ctrl-C), 1 another stop request, 101 a bug (a panic) ended it.
    pub fn exit_code(&self) -> u8 {
        match self {
            RunError::Scene(_) | RunError::Open { .. } => EXIT_NOT_STARTED,
            RunError::Device { .. } => EXIT_FAULT,
            RunError::Ended { ending, .. } => match ending {
                Ending::Stopped(r) => r.exit_code(),
                Ending::Fault => EXIT_FAULT,
                Ending::Failed => EXIT_FAILED,
                Ending::Bug => EXIT_BUG,
            },
        }
    }

    /// The stop that ended the run, if one did.
    pub fn stopped(&self) -> Option<StopReason> {
        match self {
            RunError::Ended {
                ending: Ending::Stopped(r),
                ..
            } => Some(*r),
            _ => None,
        }
    }
}
