//! Dynamixel Protocol 2.0 servo hands and the tactile grasp loop (seed 000 §5–7).
//!
//! Two halves, built separately:
//! - the servo side (`dynamixel2` over `serial2`): [control tables as data](control_table)
//!   for the MX-28 (Protocol 2.0 firmware), XM430-W350 and RH-P12-RN, and a [`ServoHand`] that
//!   implements [`hand_traits::GripperActuator`]; with the `sim` feature, [`sim`] is a
//!   Protocol 2.0 servo bus on a pseudo-terminal that the hand (or the ROBOTIS SDK) talks to;
//! - the grasp loop: tactile source → estimates → grasp policy → actuator at a fixed rate, with
//!   a defined safe state on every fault.
#![deny(unsafe_code)]

pub mod control_table;
mod error;
pub mod grasp_loop;
pub mod protocol;
mod servo_hand;
#[cfg(feature = "sim")]
pub mod sim;

pub use error::{Error, InstructionError, faults_from_hardware_error};
pub use servo_hand::{RawGoals, RawServoState, ServoHand};
