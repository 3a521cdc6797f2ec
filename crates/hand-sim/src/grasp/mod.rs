//! Grasp objects and the servo load model (seed 000 §5–7, Table 5).
//!
//! Two opposing fingers, each on an MX-28 under position control with a torque limit 0…1023,
//! squeeze one of the six Table 5 objects (or a randomised one) and lift it. Per step the model
//! exposes the servo's position, velocity, load, current and overload bit, the pad force, slip,
//! damage and the [`ContactPatch`](crate::fingertip::ContactPatch) on the fingertip.
//!
//! - [`servo`]: how the hand tunes its MX-28s (the motor is `dxl_sim::SimServo`);
//! - [`plant`]: the object as the servo's load ([`GraspPlant`]);
//! - [`linkage`]: torque-limit counts → pad force;
//! - [`object`]: the six objects, their assumed materials and the parameters derived from Table 5;
//! - [`statics`]: the settled grasp in closed form (predicted holding range);
//! - [`contact`]: the squeeze law and the fingertip cells pressed;
//! - [`rig`]: one grasp, the plain API a control loop drives ([`GraspRig`]);
//! - [`hold`]: the 2-minute hold test and the sweep that measures a holding range;
//! - [`random`]: seeded objects around the six;
//! - [`config`] / [`sim`]: the `[grasp]` table of a scene and the [`GraspSim`] model.
//!
//! ```
//! use hand_sim::grasp::{GraspRig, ObjectKind, ObjectParams, RigParams};
//! let rig = RigParams::default();
//! let cube = ObjectParams::table5(ObjectKind::Cube, &rig)?;
//! let mut g = GraspRig::new(cube, rig)?;
//! g.set_torque_limit(200)?;
//! g.close()?;
//! for _ in 0..3000 { g.step(1e-3)?; }
//! g.set_lifted(true);
//! for _ in 0..2000 { g.step(1e-3)?; }
//! let s = g.state();
//! assert!(!s.slipping && !s.damaged && s.faults.is_empty() && s.grip_force_n > 0.0);
//! # Ok::<(), hand_sim::SimError>(())
//! ```
//!
//! Calibration against Table 5 and what is not modelled: `docs/sim-calibration/grasp.md`.

pub mod config;
pub mod contact;
pub mod hold;
pub mod linkage;
pub mod object;
pub mod persist;
pub mod plant;
pub mod random;
pub mod rig;
pub mod servo;
pub mod sim;
pub mod statics;

pub use config::{GraspConfig, ObjectChoice, TorqueStep};
pub use hold::{HoldOutcome, HoldTest, run_hold, sweep_holding_range};
pub use object::{ObjectKind, ObjectParams};
pub use plant::{GraspBody, GraspPlant};
pub use random::{RandomObject, random_objects};
pub use rig::{GraspRig, GraspState, RigParams};
pub use sim::GraspSim;
pub use statics::{HoldingRange, predicted_range};
