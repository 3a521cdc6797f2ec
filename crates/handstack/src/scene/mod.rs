//! Scene files: TOML that names the parts of a hand stack and the experiment to run on it.
//!
//! ```
//! let scene = handstack::scene::Scene::parse(
//!     "weight.toml",
//!     r#"
//!     title = "Table 1"
//!     [sim]
//!     seed = 7
//!     [sensors.fingertip]
//!     osr = 4096
//!     [estimators.force]
//!     model = "sim"
//!     [experiment.weight]
//!     "#,
//! )?;
//! assert_eq!(scene.name, "weight");
//! // An OSR the MS5611 does not have names the key, the line and what is allowed.
//! let err = handstack::scene::Scene::parse("bad.toml", "title = \"x\"\n[sensors.fingertip]\nosr = 300\n[experiment.weight]\n")
//!     .unwrap_err();
//! assert!(err.to_string().starts_with("bad.toml:3:7: `sensors.fingertip.osr`"), "{err}");
//! # Ok::<(), handstack::scene::SceneError>(())
//! ```

mod error;
pub mod experiment;
pub mod parts;
mod validate;

pub use error::{Location, SceneError};

use serde::Deserialize;
use std::path::Path;
use toml::Spanned;

/// A scene file as written.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneFile {
    /// One line saying what the scene reproduces.
    pub title: String,
    /// The simulated physics (hand-sim's scene config: `seed` and one table per model). The
    /// sensor knobs (OSR, pressure mode) belong to `[sensors.*]` and are copied in.
    #[serde(default)]
    pub sim: Option<Spanned<hand_sim::scene::SceneConfig>>,
    /// The sensors.
    #[serde(default)]
    pub sensors: parts::Sensors,
    /// The estimators.
    #[serde(default)]
    pub estimators: parts::Estimators,
    /// The grasp controller.
    pub controller: Option<Spanned<parts::Controller>>,
    /// The servo hand.
    pub hand: Option<Spanned<parts::Hand>>,
    /// The arm.
    pub arm: Option<Spanned<parts::Arm>>,
    /// What to run.
    pub experiment: Spanned<experiment::Experiments>,
}

/// A parsed and validated scene.
#[derive(Debug, Clone)]
pub struct Scene {
    /// The file stem (`weight-estimation`).
    pub name: String,
    /// The file's contents as written.
    pub file: SceneFile,
    /// The simulated physics with the sensor knobs applied.
    pub sim: hand_sim::scene::SceneConfig,
}

impl Scene {
    /// Reads and validates the scene file at `path`.
    pub fn load(path: &Path) -> Result<Scene, SceneError> {
        let text = std::fs::read_to_string(path).map_err(|source| SceneError::Read {
            path: path.to_owned(),
            source,
        })?;
        Scene::parse(&path.display().to_string(), &text)
    }

    /// Parses and validates scene text; `file` names it in errors (its stem names the scene).
    pub fn parse(file: &str, text: &str) -> Result<Scene, SceneError> {
        let parsed: SceneFile =
            toml::from_str(text).map_err(|e| SceneError::syntax(file, text, &e))?;
        let sim = validate::check(&parsed, file, text)?;
        let name = Path::new(file)
            .file_stem()
            .map_or_else(|| file.to_owned(), |s| s.to_string_lossy().into_owned());
        Ok(Scene {
            name,
            file: parsed,
            sim,
        })
    }

    /// The scene's root seed (`[sim] seed`, 0 without a `[sim]` table).
    pub fn seed(&self) -> u64 {
        self.sim.seed
    }

    /// The contact locators `[estimators.contact]` names (none without that table).
    pub fn locators(&self) -> Vec<parts::Locator> {
        self.file
            .estimators
            .contact
            .as_ref()
            .map(|c| c.get_ref().locators.get_ref().clone())
            .unwrap_or_default()
    }
}
