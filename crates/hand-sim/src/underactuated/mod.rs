//! The underactuated four-finger hand of seed 001: one stepper, seesaw differentials, two
//! phalanges per finger, an FSR and a distal potentiometer per finger read by a 10-bit ADC.
//!
//! A low-dimensional, quasi-static model (see `docs/sim-calibration/underactuated.md` for the
//! calibration against the paper and what is not modelled):
//!
//! - [`hand`]: the stepper closes at constant speed, open loop; the differential shares one
//!   tendon tension among the fingers, so blocked fingers stop and the others keep closing;
//!   the stepper stalls at a tension limit.
//! - [`finger`]: torque balance of each finger's two joints against springs, 0…90° stops and
//!   the contact forces.
//! - [`contact`]: the fingertip pad in series with the object's local material, densifying,
//!   with creep for soft materials.
//! - [`object`]: shape × size × material (Table 1), per-finger local stiffness and width for
//!   irregular objects, and the seeded pose.
//! - [`fsr`], [`pot`], [`adc`]: readings leave the model only as 10-bit codes, decoded by the
//!   nominal sensor laws as the paper's Arduino + Matlab did.
//! - [`UnderactuatedConfig::other_hand`]: the same hand built again, its sensors reading
//!   differently.
//! - [`grasp`] records a series from first contact to 14 s; [`dataset`] builds the paper's
//!   training and test grasps; [`separability`] is a nearest-centroid sanity check, a floor;
//!   [`ceiling`] the Bayes rule on the exact local moduli, the most a classifier can expect.

pub mod adc;
pub mod ceiling;
pub mod config;
pub mod contact;
pub mod dataset;
pub mod finger;
pub mod fsr;
pub mod grasp;
pub mod hand;
pub mod object;
pub mod other;
pub mod pot;
pub mod separability;
mod solve;

pub use adc::Adc;
pub use config::{SensorConfig, UnderactuatedConfig};
pub use finger::{FingerParams, FingerState};
pub use fsr::Fsr;
pub use grasp::{GraspSeries, record_grasp};
pub use hand::{SensorCodes, SensorVolts, Underactuated};
pub use object::{Material, ObjectConfig, Pose, PoseConfig, Shape};
pub use pot::Pot;
