//! Scenes: a TOML file names the models a run needs; only those are built and stepped.
//!
//! ```toml
//! seed = 42          # every random stream of every model derives from it
//! # [<model>]        # one table per model the scene needs, e.g. [imu_pad]; absent: not built
//! ```
//!
//! Adding a model: a `pub <name>: Option<Config>` field here, the same name in [`Scene`], one
//! line each in [`Scene::build`], [`Scene::step_to`] and [`Scene::models`].

use crate::SimError;
use crate::fingertip::{Fingertip, FingertipConfig};
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
    /// The barometric fingertip (seed 000), if the scene needs it.
    pub fingertip: Option<FingertipConfig>,
    /// `[grasp]`: Table 5 objects between two MX-28 fingers.
    pub grasp: Option<crate::grasp::GraspConfig>,
    /// The ICM-20789 pad (seed 002), if the scene needs it.
    pub imu_pad: Option<crate::imu_pad::ImuPadConfig>,
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
pub struct Scene {
    /// The scene seed.
    pub seed: u64,
    /// The barometric fingertip, if built.
    pub fingertip: Option<Fingertip>,
    /// The grasp model, if the scene names it.
    pub grasp: Option<crate::grasp::GraspSim>,
    /// The ICM-20789 pad, if built.
    pub imu_pad: Option<crate::imu_pad::ImuPad>,
    /// The underactuated hand, if the scene names it.
    pub underactuated: Option<crate::underactuated::Underactuated>,
    now_ns: u64,
}

impl Scene {
    /// Builds exactly the models `config` names.
    pub fn build(config: &SceneConfig) -> Result<Scene, SimError> {
        let seed = config.seed;
        Ok(Scene {
            seed,
            fingertip: config
                .fingertip
                .as_ref()
                .map(|c| Fingertip::new(c, seed))
                .transpose()?,
            grasp: config
                .grasp
                .as_ref()
                .map(|c| crate::grasp::GraspSim::new(c, seed))
                .transpose()?,
            imu_pad: config
                .imu_pad
                .as_ref()
                .map(|c| crate::imu_pad::ImuPad::new(c, seed))
                .transpose()?,
            underactuated: config
                .underactuated
                .as_ref()
                .map(|c| crate::underactuated::Underactuated::new(c, seed))
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
        step(&mut self.fingertip, t_ns)?;
        step(&mut self.grasp, t_ns)?;
        step(&mut self.imu_pad, t_ns)?;
        step(&mut self.underactuated, t_ns)?;
        self.now_ns = self.now_ns.max(t_ns);
        Ok(())
    }

    /// The names of the models this scene built.
    pub fn models(&self) -> Vec<&'static str> {
        let mut built = Vec::new();
        name_if_built(&self.fingertip, &mut built);
        name_if_built(&self.grasp, &mut built);
        name_if_built(&self.imu_pad, &mut built);
        name_if_built(&self.underactuated, &mut built);
        built
    }
}

fn step<M: Model>(model: &mut Option<M>, t_ns: u64) -> Result<(), SimError> {
    model.as_mut().map_or(Ok(()), |m| m.step_to(t_ns))
}

fn name_if_built<M: Model>(model: &Option<M>, built: &mut Vec<&'static str>) {
    if model.is_some() {
        built.push(M::NAME);
    }
}
