//! Scenes: a TOML file names the models a run needs; only those are built and stepped.
//!
//! ```toml
//! seed = 42          # every random stream of every model derives from it
//! # [<model>]        # one table per model the scene needs, e.g. [imu_pad]; absent: not built
//! ```
//!
//! Adding a model: a `pub <name>: Option<Config>` field here, the same name in [`Scene`], one
//! line in [`Scene::build`] and one in [`Scene::step_to`].

use crate::SimError;
use serde::Deserialize;

/// A physical model a scene can hold: stepped on the scene's simulated clock.
pub trait Model {
    /// The model's name, as its table in a scene file.
    const NAME: &'static str;

    /// Advances the model to simulated time `t_ns` (no-op if it is already there).
    fn step_to(&mut self, t_ns: u64) -> Result<(), SimError>;

    /// How many internal steps the model has taken since it was built.
    fn steps(&self) -> u64;
}

/// What a scene file holds.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneConfig {
    /// Root of every random stream in the scene.
    pub seed: u64,
    /// The underactuated hand of seed 001.
    pub underactuated: Option<crate::underactuated::UnderactuatedConfig>,
}

impl SceneConfig {
    /// Parses a scene file; errors name the line and the key.
    pub fn from_toml(text: &str) -> Result<SceneConfig, SimError> {
        Ok(toml::from_str(text)?)
    }
}

/// The models a scene built, each `None` unless its config names it.
#[derive(Debug)]
pub struct Scene {
    /// The scene seed.
    pub seed: u64,
    /// The underactuated hand, if the scene names it.
    pub underactuated: Option<crate::underactuated::Underactuated>,
    now_ns: u64,
}

impl Scene {
    /// Builds exactly the models `config` names.
    pub fn build(config: &SceneConfig) -> Result<Scene, SimError> {
        Ok(Scene {
            seed: config.seed,
            underactuated: (config.underactuated.as_ref())
                .map(|c| crate::underactuated::Underactuated::new(c, config.seed))
                .transpose()?,
            now_ns: 0,
        })
    }

    /// Simulated time, ns.
    pub fn now_ns(&self) -> u64 {
        self.now_ns
    }

    /// Steps every built model to `t_ns`; the models that were not built are not touched.
    pub fn step_to(&mut self, t_ns: u64) -> Result<(), SimError> {
        if let Some(m) = &mut self.underactuated {
            m.step_to(t_ns)?;
        }
        self.now_ns = self.now_ns.max(t_ns);
        Ok(())
    }

    /// The names of the models this scene built.
    pub fn models(&self) -> Vec<&'static str> {
        let mut names = Vec::new();
        if self.underactuated.is_some() {
            names.push(<crate::underactuated::Underactuated as Model>::NAME);
        }
        names
    }
}
