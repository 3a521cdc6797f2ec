//! Seeded objects around the six of Table 5, for the closed-loop tests (the holds repeated on 20
//! randomised objects). Each draws a base object and perturbs its mass, friction, stiffness,
//! crush force and size; its holding range is then *derived* from the statics, not assumed.

use rand::Rng;

use super::object::{ObjectKind, ObjectParams};
use super::rig::RigParams;
use super::statics::{HoldingRange, predicted_range};
use crate::SimError;
use crate::seed;

/// The narrowest holding range a randomised object may have, counts: a controller needs room.
pub const MIN_RANGE_WIDTH: u16 = 20;
/// Draws per object before giving up on finding a holdable one.
const MAX_DRAWS: usize = 64;

/// One randomised object.
#[derive(Debug, Clone, PartialEq)]
pub struct RandomObject {
    /// The Table 5 object it varies.
    pub base: ObjectKind,
    /// Its parameters.
    pub params: ObjectParams,
    /// The torque limits that hold it (settled statics).
    pub range: HoldingRange,
}

/// `n` objects from the scene seed's `"grasp"` stream; object `i` varies Table 5 object
/// `i mod 6`. Mass ±20 %, friction ±15 %, crush force ±15 %, size ±10 %, stiffness ×0.7…1.4
/// (log-uniform); redrawn while the range is narrower than [`MIN_RANGE_WIDTH`].
pub fn random_objects(
    scene_seed: u64,
    n: usize,
    rig: &RigParams,
) -> Result<Vec<RandomObject>, SimError> {
    let mut rng = seed::stream(scene_seed, "grasp");
    let mut out = Vec::with_capacity(n);
    for i in 0..n {
        let base = ObjectKind::ALL[i % ObjectKind::ALL.len()];
        let nominal = ObjectParams::table5(base, rig)?;
        let found = (0..MAX_DRAWS).find_map(|_| {
            let params = perturb(&nominal, &mut rng, format!("random_{i}_{}", base.name()));
            let range = predicted_range(&params, rig)?;
            (range.max - range.min >= MIN_RANGE_WIDTH).then_some(RandomObject {
                base,
                params,
                range,
            })
        });
        out.push(found.ok_or_else(|| {
            SimError::config(
                "random object",
                format!("no holdable {i} in {MAX_DRAWS} draws"),
            )
        })?);
    }
    Ok(out)
}

fn perturb(nominal: &ObjectParams, rng: &mut impl Rng, name: String) -> ObjectParams {
    let mut u = |spread: f64| 1.0 + rng.random_range(-spread..=spread);
    let mut p = nominal.clone();
    p.name = name;
    p.mass_kg *= u(0.20);
    p.material.friction *= u(0.15);
    p.damage_force_n *= u(0.15);
    let size = u(0.10);
    p.material.width_m *= size;
    p.material.face_m = p.material.face_m.map(|f| f * size);
    p.material.radius_m = p.material.radius_m.map(|r| r.map(|r| r * size));
    let log_k = rng.random_range(0.7_f64.ln()..=1.4_f64.ln());
    p.material.stiffness_n_per_m *= log_k.exp();
    p
}
