//! Dynamixel Protocol 2.0 servo hands and the tactile grasp loop (seed 000 §5–7).
//!
//! Two halves, built separately:
//! - the servo side (`dynamixel2` over `serial2`): [control tables as data](control_table)
//!   for the MX-28 (Protocol 2.0 firmware), XM430-W350 and RH-P12-RN, and a [`ServoHand`] that
//!   implements [`hand_traits::GripperActuator`]; with the `sim` feature, [`sim`] is a
//!   Protocol 2.0 servo bus on a pseudo-terminal that the hand (or the ROBOTIS SDK) talks to;
//! - the grasp loop: tactile source → estimates → grasp policy → actuator at a fixed rate, with
//!   a defined safe state on every fault.
//!
//! The same driver code runs on hardware (`ServoHand::open("/dev/ttyUSB0", 1_000_000, &ids)`)
//! and against the simulator:
//!
//! ```
//! use hand_control::sim::{Fault, SimBus, SimConfig};
//! use hand_control::{Error, ServoHand};
//! use hand_traits::{Effort, GripperActuator, GripperCommand, SafeAction};
//! use std::time::Duration;
//!
//! let (mut sim, port) = SimBus::spawn(SimConfig::with_ids(&[1, 2]))?;
//! // Pings both and identifies MX-28(2.0); the simulator gets a generous reply allowance.
//! let mut hand = ServoHand::with_reply_latency(port, &[1, 2], hand_control::sim::REPLY_LATENCY)?;
//! hand.set_torque(true)?;
//! // The paper's torque limit 400 of 0…1023, closing towards 3.5 rad.
//! let cmd = GripperCommand { position_rad: 3.5, effort: Effort::from_torque_limit_raw(400) };
//! hand.command(&cmd)?; // two sync writes: Goal PWM 346 of 885, Goal Position
//! sim.advance(Duration::from_millis(500))?; // simulated time, no sleeping
//! assert!(hand.state()?.faults.is_empty()); // one sync read
//! // A servo that stops answering is a typed error; the broadcast torque-off still reaches it.
//! sim.inject(2, Fault::Mute);
//! assert!(matches!(hand.state(), Err(Error::Timeout { id: Some(2) })));
//! hand.safe_stop(SafeAction::TorqueOff)?;
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
#![deny(unsafe_code)]

pub mod control_table;
mod error;
#[doc(hidden)]
pub mod fuzzing;
pub mod grasp_loop;
pub mod protocol;
mod servo_hand;
#[cfg(feature = "sim")]
pub mod sim;

pub use error::{Error, InstructionError, faults_from_hardware_error};
pub use servo_hand::{
    DEFAULT_REPLY_LATENCY, GoalPackets, PacketCounts, RawGoals, RawServoState, ServoHand,
    encode_goals,
};
