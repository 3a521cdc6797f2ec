//! [`GraspSim`]: the scene model — one hand per configured object, stepped at a fixed dt.

use super::config::{GraspConfig, ObjectChoice};
use super::object::ObjectParams;
use super::random::random_objects;
use super::rig::{GraspRig, GraspState};
use super::statics::predicted_range;
use crate::SimError;
use crate::scene::Model;

/// The grasp model of a scene.
#[derive(Debug)]
pub struct GraspSim {
    config: GraspConfig,
    rigs: Vec<GraspRig>,
    dt_ns: u64,
    end_ns: u64,
    now_ns: u64,
    next_change: usize,
    steps: u64,
}

impl GraspSim {
    /// Builds the hands `config` names; random objects come from `scene_seed`.
    pub fn new(config: &GraspConfig, scene_seed: u64) -> Result<GraspSim, SimError> {
        config.validate()?;
        let mut config = config.clone();
        config.schedule.sort_by(|a, b| a.at_s.total_cmp(&b.at_s));
        let randoms = config
            .objects
            .iter()
            .filter_map(|o| match o {
                ObjectChoice::Random(i) => Some(usize::from(*i) + 1),
                ObjectChoice::Table5(_) => None,
            })
            .max()
            .map_or(Ok(Vec::new()), |n| {
                random_objects(scene_seed, n, &config.rig)
            })?;
        let rigs = config
            .objects
            .iter()
            .map(|o| {
                let object = match o {
                    ObjectChoice::Table5(kind) => ObjectParams::table5(*kind, &config.rig)?,
                    ObjectChoice::Random(i) => randoms[usize::from(*i)].params.clone(),
                };
                let limit = match config.torque_limit {
                    Some(l) => l,
                    None => predicted_range(&object, &config.rig)
                        .map_or(0, |r| r.min + (r.max - r.min) / 2),
                };
                let mut rig = GraspRig::new(object, config.rig)?;
                rig.set_torque_limit(limit)?;
                rig.close()?;
                Ok(rig)
            })
            .collect::<Result<Vec<_>, SimError>>()?;
        let to_ns = |s: f64| (s * 1e9).round().max(0.0) as u64;
        Ok(GraspSim {
            dt_ns: to_ns(config.dt_s).max(1),
            end_ns: to_ns(config.duration_s),
            config,
            rigs,
            now_ns: 0,
            next_change: 0,
            steps: 0,
        })
    }

    /// The hands, in the order of `objects`.
    pub fn rigs(&self) -> &[GraspRig] {
        &self.rigs
    }

    /// A hand, to drive it directly between steps.
    pub fn rig_mut(&mut self, i: usize) -> Option<&mut GraspRig> {
        self.rigs.get_mut(i)
    }

    /// Every hand's present state.
    pub fn states(&self) -> Vec<GraspState> {
        self.rigs.iter().map(GraspRig::state).collect()
    }

    /// Simulated time, ns.
    pub fn now_ns(&self) -> u64 {
        self.now_ns
    }

    fn step_once(&mut self) -> Result<(), SimError> {
        let t_s = self.now_ns as f64 * 1e-9;
        while let Some(change) = self.config.schedule.get(self.next_change) {
            if change.at_s > t_s {
                break;
            }
            for rig in &mut self.rigs {
                rig.set_torque_limit(change.torque_limit)?;
            }
            self.next_change += 1;
        }
        let lifted = t_s >= self.config.lift_at_s;
        for rig in &mut self.rigs {
            rig.set_lifted(lifted);
            rig.step(self.config.dt_s)?;
        }
        self.now_ns += self.dt_ns;
        self.steps += 1;
        Ok(())
    }
}

impl Model for GraspSim {
    const NAME: &'static str = "grasp";

    fn step_to(&mut self, t_ns: u64) -> Result<(), SimError> {
        let until = t_ns.min(self.end_ns);
        while self.now_ns + self.dt_ns <= until {
            self.step_once()?;
        }
        Ok(())
    }

    fn steps(&self) -> u64 {
        self.steps
    }
}
