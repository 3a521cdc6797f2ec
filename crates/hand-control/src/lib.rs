//! Dynamixel Protocol 2.0 servo hands and the tactile grasp loop (seed 000 §5–7).
//!
//! Two halves, built separately:
//! - the servo side (`dynamixel2` over `serial2`): control tables as data, a servo hand that
//!   implements [`hand_traits::GripperActuator`], and with the `sim` feature a Protocol 2.0
//!   servo bus on a pseudo-terminal;
//! - the grasp loop: tactile source → estimates → grasp policy → actuator at a fixed rate, with
//!   a defined safe state on every fault.
#![deny(unsafe_code)]

pub mod grasp_loop;
