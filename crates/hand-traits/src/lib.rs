//! The narrow traits a tactile robot hand stack composes through.
//!
//! Each trait is one step of the loop *tactile frames → force / contact / softness estimates →
//! grasp policy → gripper*, with an arm alongside. A scene composes whichever implementations it
//! names; a user replaces any one of them by implementing a trait of two or three methods.
//!
//! The value types carry their unit in every field name (`force_n`, `pressure_pa`,
//! `position_rad`) so that a value never travels without its unit.
//!
//! ```
//! use hand_traits::{Effort, GraspObservation, GraspPolicy};
//!
//! /// A proportional policy: more effort the further the pressure is below target.
//! struct Proportional { gain_per_pa: f32 }
//!
//! impl GraspPolicy for Proportional {
//!     type Error = core::convert::Infallible;
//!     fn effort(&mut self, obs: &GraspObservation) -> Result<Effort, Self::Error> {
//!         Ok(Effort::saturating(obs.pressure_error_pa * self.gain_per_pa))
//!     }
//! }
//!
//! let mut policy = Proportional { gain_per_pa: 1e-3 };
//! let effort = policy.effort(&GraspObservation { pressure_error_pa: 400.0, pressure_rate_pa_per_s: 0.0 })?;
//! assert_eq!(effort.to_torque_limit_raw(), 409); // 0.4 of the MX-28's 0…1023 scale
//! # Ok::<(), core::convert::Infallible>(())
//! ```
//!
//! Feature `sim` adds `sim::SimClock`, the simulated time every simulated device of the
//! stack shares (std-free: `alloc` and 64-bit atomics); firmware leaves it off, and the crate
//! then has no dependency at all.
#![no_std]
#![forbid(unsafe_code)]

#[cfg(feature = "sim")]
extern crate alloc;

mod arm;
mod contact;
mod force;
mod frames;
mod gripper;
mod policy;
#[cfg(feature = "sim")]
pub mod sim;
mod softness;
mod source;

pub use arm::{Arm, LinearMotion, Pose};
pub use contact::{Contact, ContactLocator};
pub use force::{ForceEstimate, ForceEstimator, GRAM_FORCE_N};
pub use frames::{FingerFrame, ImuFrame, PressureFrame};
pub use gripper::{Faults, GripperActuator, GripperCommand, GripperState, SafeAction};
pub use policy::{Effort, GraspObservation, GraspPolicy};
pub use softness::{Softness, SoftnessClassifier};
pub use source::TactileSource;
