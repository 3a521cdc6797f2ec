//! Errors of a paper scene: the stack's ([`handstack::RunError`]: the scene file, a device that
//! cannot be opened or fails) or the reproduction's own (physics, models, datasets, fixtures).

use handstack::RunError;
use handstack::scene::SceneError;

/// Why a paper scene could not run to its end.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// The stack failed: the scene file, or a device.
    #[error(transparent)]
    Run(#[from] RunError),
    /// The simulated physics refused a configuration or a driver failed.
    #[error("simulation: {0}")]
    Sim(#[from] hand_sim::SimError),
    /// A model failed to load or evaluate.
    #[error("model: {0}")]
    Net(#[from] tactile_nets::NetError),
    /// A committed dataset could not be read.
    #[error("dataset: {0}")]
    Data(#[from] paper_experiments::data::DatasetError),
    /// A paper fixture failed to load.
    #[error("paper fixture: {0}")]
    Fixture(#[from] paper_fixtures::FixtureError),
}

/// A training or evaluation job's error is its dataset's, its model's or its simulation's.
impl From<paper_experiments::jobs::JobError> for Error {
    fn from(e: paper_experiments::jobs::JobError) -> Error {
        match e {
            paper_experiments::jobs::JobError::Data(e) => Error::Data(e),
            paper_experiments::jobs::JobError::Net(e) => Error::Net(e),
            paper_experiments::jobs::JobError::Sim(e) => Error::Sim(e),
        }
    }
}

impl From<SceneError> for Error {
    fn from(e: SceneError) -> Error {
        Error::Run(RunError::Scene(e))
    }
}

/// A device failure as a paper-scene error.
pub(crate) fn device(device: &'static str, reason: impl Into<String>) -> Error {
    Error::Run(RunError::Device {
        device,
        reason: reason.into(),
    })
}

/// A stack error keeps `handstack run`'s exit status; the reproduction's own errors give 1.
impl handstack::summary::ExitStatus for Error {
    fn exit_code(&self) -> u8 {
        match self {
            Error::Run(e) => e.exit_code(),
            _ => 1,
        }
    }
}
