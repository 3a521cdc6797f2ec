//! The force DNN a scene names, ready to estimate: one built into tactile-nets, or a weights
//! file of the user's own fingertip (`[estimators.force] weights`, read when the scene is).

use super::parts::ForceModel;
use hand_traits::{ForceEstimate, ForceEstimator};
use std::path::{Path, PathBuf};
use tactile_nets::NetError;
use tactile_nets::force_dnn::ForceDnn;

/// A scene's force DNN.
#[derive(Debug, Clone)]
pub enum ForceNet {
    /// A model built into tactile-nets.
    BuiltIn(ForceModel),
    /// A weights file.
    File {
        /// Where it was read from.
        path: PathBuf,
        /// The model.
        dnn: ForceDnn,
    },
}

impl ForceNet {
    /// The weights file at `path`.
    ///
    /// Errors: the file's, naming it (unreadable, not a force DNN, misshapen tensors).
    pub fn load(path: &Path) -> Result<ForceNet, NetError> {
        Ok(ForceNet::File {
            path: path.to_owned(),
            dnn: ForceDnn::load(path)?,
        })
    }

    /// How a user names it: the built-in model's name, or the file.
    pub fn describe(&self) -> String {
        match self {
            ForceNet::BuiltIn(m) => format!("the built-in `{}` model", m.name()),
            ForceNet::File { path, .. } => path.display().to_string(),
        }
    }

    /// The weight, gf, for the three tared rises `rise_hpa` (hPa).
    ///
    /// Errors: an input of the wrong length, not finite, or so far outside the training range
    /// that the network overflows.
    pub fn estimate_gf(&self, rise_hpa: &[f32]) -> Result<f32, NetError> {
        match self {
            ForceNet::BuiltIn(m) => Ok(m.dnn().estimate_gf(rise_hpa)?),
            ForceNet::File { dnn, .. } => dnn.estimate_gf(rise_hpa),
        }
    }
}

/// Input: the three tared rises, hPa; the estimate is flagged out of range beyond the model's
/// rated range, as tactile-nets' models flag it.
impl ForceEstimator for ForceNet {
    type Input = [f32];
    type Error = NetError;

    fn estimate_force(&mut self, input: &[f32]) -> Result<ForceEstimate, NetError> {
        match self {
            ForceNet::BuiltIn(m) => Ok(m.dnn().estimate_force(input)?),
            ForceNet::File { dnn, .. } => dnn.estimate_force(input),
        }
    }
}
