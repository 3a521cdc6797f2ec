//! Paper scene files: a handstack scene (its parts, checked by `handstack::scene`) whose
//! `[experiment]` table holds the papers' protocols ([`Experiments`]) and whose `[sim]` table
//! is hand-sim's physics for every device the scene does not read from hardware.
//!
//! ```
//! let scene = paper_scenes::scene::PaperScene::parse(
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
//! assert_eq!(scene.seed(), 7);
//! // A knob of the sensor repeated in [sim] names the key, the line and where it belongs.
//! let err = paper_scenes::scene::PaperScene::parse(
//!     "bad.toml",
//!     "title = \"x\"\n[sim]\nseed = 1\n[sim.fingertip]\nosr = 1024\n[sensors.fingertip]\nosr = 1024\n[experiment.readout]\nframes = 5\n",
//! )
//! .unwrap_err();
//! assert!(err.to_string().starts_with("bad.toml:5:7: `sim.fingertip.osr`"), "{err}");
//! # Ok::<(), handstack::scene::SceneError>(())
//! ```

pub mod experiments;
mod sim;

pub use experiments::Experiments;
pub use sim::ArmSim;

use hand_sim::scene::SceneConfig;
use handstack::scene::{Checker, SceneError, SceneOf};
use std::path::Path;

/// A parsed and validated paper scene.
#[derive(Debug, Clone)]
pub struct PaperScene {
    /// The scene: its name, parts and experiments.
    pub scene: SceneOf<Experiments>,
    /// The simulated physics with the sensor knobs applied.
    pub sim: SceneConfig,
    /// `[sim.arm]`: the UR controller simulator, for an `[arm]` without a host.
    pub arm_sim: ArmSim,
}

impl core::ops::Deref for PaperScene {
    type Target = SceneOf<Experiments>;
    fn deref(&self) -> &SceneOf<Experiments> {
        &self.scene
    }
}

impl PaperScene {
    /// Reads and validates the paper scene file at `path`.
    pub fn load(path: &Path) -> Result<PaperScene, SceneError> {
        let text = handstack::scene::read(path)?;
        PaperScene::parse(&path.display().to_string(), &text)
    }

    /// Parses and validates scene text; `file` names it in errors.
    pub fn parse(file: &str, text: &str) -> Result<PaperScene, SceneError> {
        let scene = SceneOf::<Experiments>::parse(file, text)?;
        let (sim, arm_sim) = sim::check(&scene.file, &Checker::new(file, text))?;
        Ok(PaperScene {
            scene,
            sim,
            arm_sim,
        })
    }

    /// The scene's root seed (`[sim] seed`, 0 without a `[sim]` table).
    pub fn seed(&self) -> u64 {
        self.sim.seed
    }

    /// Its `[experiment.tap]`, if it names one.
    pub fn tap(&self) -> Option<&experiments::Tap> {
        self.file
            .experiment
            .get_ref()
            .tap
            .as_ref()
            .map(|t| t.get_ref())
    }
}
