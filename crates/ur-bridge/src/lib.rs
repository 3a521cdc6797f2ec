//! Universal Robots arms through ur_rtde.
//!
//! - [`UrArm`] (feature `rtde-client`, on by default): `hand_traits::Arm` over ur_rtde's
//!   `rtde_control` / `rtde_receive` / `dashboard_client`, embedded with pyo3 (the
//!   site-packages of a [`Venv`]). moveL / moveJ, blocking or asynchronous with progress, stopL,
//!   speedL, TCP pose, joint angles, robot and safety status; Python exceptions and refused
//!   commands become [`UrError`]s.
//! - [`kinematics`]: a UR3 (DH table, Jacobian, inverse kinematics near a seed, limits).
//! - [`status`]: robot, safety and runtime states and status bits as RTDE reports them.
//! - [`rtde_frame`]: RTDE's package framing.
//!
//! Without default features the crate is the arm's model and RTDE's framing only, in plain
//! Rust: no pyo3, no Python needed to build it.

#[cfg(feature = "rtde-client")]
mod bridge;
#[cfg(feature = "rtde-client")]
mod error;
pub mod kinematics;
#[cfg(feature = "rtde-client")]
mod python;
pub mod rtde_frame;
pub mod status;

#[cfg(feature = "rtde-client")]
pub use bridge::{JointMotion, MoveHandle, MoveProgress, UrArm, UrConfig};
#[cfg(feature = "rtde-client")]
pub use error::UrError;
/// The `hand-traits` types of this crate's API, so that a user needs no other crate.
pub use hand_traits::{Arm, LinearMotion, Pose};
#[cfg(feature = "rtde-client")]
pub use python::{PYTHON_ENV, VENV_ENV, Venv};
