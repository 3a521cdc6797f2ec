//! Universal Robots arms through ur_rtde, for tactile-hand experiments.
//!
//! - [`UrArm`]: `hand_traits::Arm` over ur_rtde's `rtde_control` / `rtde_receive` /
//!   `dashboard_client`, embedded with pyo3 (the site-packages of a [`Venv`]). moveL / moveJ,
//!   blocking or asynchronous with progress, stopL, speedL, TCP pose, joint angles, robot and
//!   safety status; Python exceptions and refused commands become [`UrError`]s.
//! - [`kinematics`]: a UR3 (DH table, Jacobian, inverse kinematics near a seed, limits).
//! - [`RegionToGrid`]: the 9 touched regions of a pad → 9 tool poses, validated against the
//!   UR3's reach and joint limits; [`tap_to_move`]: the tap → region → move loop of seed 002 §IV-B over `hand-traits` parts.
//! - `sim` feature: [`sim::UrSim`], a UR controller on loopback the unmodified ur_rtde accepts.

mod bridge;
mod error;
mod grid;
pub mod kinematics;
mod python;
mod rtde_frame;
#[cfg(feature = "sim")]
pub mod sim;
pub mod status;
pub mod tap_to_move;

pub use bridge::{JointMotion, MoveHandle, MoveProgress, UrArm, UrConfig};
pub use error::UrError;
pub use grid::{GridError, REGIONS, RegionToGrid};
/// The `hand-traits` types of this crate's API, so that a user needs no other crate.
pub use hand_traits::{Arm, LinearMotion, Pose};
pub use python::{PYTHON_ENV, VENV_ENV, Venv};
