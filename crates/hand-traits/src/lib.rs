//! The narrow traits a tactile robot hand stack composes through.
//!
//! Each trait is one step of the loop *tactile frames → force / contact / softness estimates →
//! grasp policy → gripper*, with an arm alongside. A scene composes whichever implementations it
//! names. The README follows (its example runs as this crate's doctest).
//!
#![doc = include_str!("../README.md")]
#![no_std]
#![forbid(unsafe_code)]

mod arm;
mod contact;
mod estimate;
mod force;
mod frames;
mod gripper;
mod policy;
mod softness;
mod source;

pub use arm::{Arm, LinearMotion, Pose};
pub use contact::{Contact, ContactLocator};
pub use estimate::{ContactEstimate, EstimateError, PressureEstimator};
pub use force::{ForceEstimate, ForceEstimator, GRAM_FORCE_N};
pub use frames::{FingerFrame, ImuFrame, PressureFrame};
pub use gripper::{Faults, GripperActuator, GripperCommand, GripperState, SafeAction};
pub use policy::{Effort, GraspObservation, GraspPolicy};
pub use softness::{Softness, SoftnessClassifier};
pub use source::TactileSource;
