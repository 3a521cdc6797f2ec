//! `papers train MODEL`: trains one committed model family with a progress bar and writes
//! its weights and metrics — the code `cargo xtask train MODEL` runs before drawing the
//! plots and docs ([`crate::jobs`]).

use std::path::{Path, PathBuf};
use thiserror::Error;

/// A trainable model family.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Model {
    /// The fingertip's contact-area MLP (seed 000 §4).
    ContactMlp,
    /// The force / weight DNN (seed 000 Table 1 and the simulated series).
    ForceDnn,
    /// The softness classifier (seed 001).
    Softness,
    /// The ICM-20789 pad's contact CNN (seed 002 §IV-A).
    ContactCnn,
}

impl Model {
    /// Every model, with its command-line name.
    pub const ALL: [(Model, &'static str); 4] = [
        (Model::ContactMlp, "contact-mlp"),
        (Model::ForceDnn, "force-dnn"),
        (Model::Softness, "softness"),
        (Model::ContactCnn, "contact-cnn"),
    ];

    /// The model named `name` on the command line.
    ///
    /// ```
    /// use paper_experiments::train::Model;
    /// assert_eq!(Model::from_name("force-dnn").ok(), Some(Model::ForceDnn));
    /// assert!(Model::from_name("cnn").unwrap_err().to_string().contains("contact-cnn"));
    /// ```
    pub fn from_name(name: &str) -> Result<Model, TrainError> {
        Model::ALL
            .iter()
            .find(|(_, n)| *n == name)
            .map(|(m, _)| *m)
            .ok_or_else(|| TrainError::UnknownModel(name.to_owned()))
    }
}

/// Options for quick experiments (each writes nothing) and partial runs.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct TrainOptions {
    /// contact-mlp, contact-cnn: train this many epochs (no search; nothing written).
    pub epochs: Option<usize>,
    /// contact-cnn: only the protocol rows whose label starts with this; softness: only the
    /// optimiser with this index (0 = LM, 1 = Adam). Nothing written for contact-cnn.
    pub only: Option<String>,
    /// softness: train and report, write nothing.
    pub dry_run: bool,
}

/// What `papers train` can fail with.
#[derive(Debug, Error)]
pub enum TrainError {
    /// No such model.
    #[error("unknown model `{0}`: expected contact-mlp, force-dnn, softness or contact-cnn")]
    UnknownModel(String),
    /// An option the model does not take, or a malformed value.
    #[error("{model}: {detail}")]
    Option {
        /// The model's name.
        model: &'static str,
        /// What is wrong.
        detail: String,
    },
    /// Reading Table 1.
    #[error("Table 1 (fixtures/paper): {0}")]
    Paper(String),
    /// Reading the dataset, training or writing.
    #[error(transparent)]
    Job(#[from] crate::jobs::JobError),
}

fn name(model: Model) -> &'static str {
    Model::ALL
        .iter()
        .find(|(m, _)| *m == model)
        .map_or("?", |(_, n)| *n)
}

/// Trains `model` on the committed data below the workspace root `root`; returns the files
/// written (none for a quick experiment).
///
/// Errors: [`TrainError::Option`] for an option `model` does not take, else what training
/// reports.
pub fn run(root: &Path, model: Model, options: &TrainOptions) -> Result<Vec<PathBuf>, TrainError> {
    let refuse = |what: &str| TrainError::Option {
        model: name(model),
        detail: format!("takes no {what}"),
    };
    let TrainOptions {
        epochs,
        only,
        dry_run,
    } = options;
    if *dry_run && model != Model::Softness {
        return Err(refuse("--dry-run"));
    }
    if epochs.is_some() && matches!(model, Model::ForceDnn | Model::Softness) {
        return Err(refuse("--epochs"));
    }
    if only.is_some() && matches!(model, Model::ForceDnn | Model::ContactMlp) {
        return Err(refuse("--only"));
    }
    Ok(match model {
        Model::ContactMlp => crate::jobs::contact_mlp(root, *epochs)?,
        Model::ForceDnn => {
            let rows: Vec<(f64, [f64; 3])> =
                paper_fixtures::seed000::table1_weight_in(&root.join("fixtures"))
                    .map_err(|e| TrainError::Paper(e.to_string()))?
                    .iter()
                    .map(|r| (r.weight_gf, r.pressure_hpa))
                    .collect();
            crate::jobs::force_dnn(root, &rows)?
        }
        Model::Softness => {
            let only = only
                .as_deref()
                .map(|s| {
                    s.parse::<usize>()
                        .ok()
                        .filter(|&i| i < crate::softness_eval::OPTIMISERS.len())
                        .ok_or_else(|| TrainError::Option {
                            model: name(model),
                            detail: format!("--only takes 0 (LM) or 1 (Adam), not `{s}`"),
                        })
                })
                .transpose()?;
            crate::jobs::softness(root, only, *dry_run)?
        }
        Model::ContactCnn => crate::jobs::contact_cnn(root, *epochs, only.as_deref())?,
    })
}

/// The workspace root for the committed data: `start` or its nearest ancestor holding
/// `crates/tactile-nets/models` (so the commands work from any directory of a checkout).
///
/// ```
/// let here = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
/// let root = paper_experiments::train::find_root(here).unwrap();
/// assert!(root.join("crates/tactile-nets/models").is_dir());
/// ```
pub fn find_root(start: &Path) -> Option<PathBuf> {
    start
        .ancestors()
        .find(|d| d.join("crates/tactile-nets/models").is_dir())
        .map(Path::to_path_buf)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn options_a_model_does_not_take_are_refused_before_training() {
        let root = Path::new("/nonexistent");
        let dry = TrainOptions {
            dry_run: true,
            ..TrainOptions::default()
        };
        let e = run(root, Model::ForceDnn, &dry).unwrap_err();
        assert_eq!(e.to_string(), "force-dnn: takes no --dry-run");
        let epochs = TrainOptions {
            epochs: Some(3),
            ..TrainOptions::default()
        };
        assert!(matches!(
            run(root, Model::Softness, &epochs),
            Err(TrainError::Option { .. })
        ));
        let only = TrainOptions {
            only: Some("7".into()),
            ..TrainOptions::default()
        };
        let e = run(root, Model::Softness, &only).unwrap_err();
        assert!(
            e.to_string().contains("--only takes 0 (LM) or 1 (Adam)"),
            "{e}"
        );
        // A valid option on a missing workspace fails on the data, not with a panic.
        assert!(matches!(
            run(root, Model::ContactMlp, &epochs),
            Err(TrainError::Job(crate::jobs::JobError::Data(_)))
        ));
    }
}
