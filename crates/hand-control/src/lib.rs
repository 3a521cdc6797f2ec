//! Dynamixel Protocol 2.0 servo hands and a tactile grasp loop, after the grasping paper of
//! Kim, Lee, Chung and Lee, *Artificial Intelligence-Based Optimal Grasping Control* (2020),
//! §5–7.
//!
//! Two halves, built separately:
//! - the servo side (`dynamixel2` over `serial2`): [control tables as data](control_table)
//!   for the MX-28 (Protocol 2.0 firmware), XM430-W350 and RH-P12-RN, and a [`ServoHand`] that
//!   implements [`hand_traits::GripperActuator`];
//! - the grasp loop: tactile source → estimates → grasp policy → actuator at a fixed rate, with
//!   a defined safe state on every fault.
//!
//! ```no_run
//! use hand_control::{Error, ServoHand};
//! use hand_traits::{Effort, GripperActuator, GripperCommand, SafeAction};
//!
//! // Pings both servos and identifies them by model number (here MX-28(2.0)).
//! let mut hand = ServoHand::open("/dev/ttyUSB0", 1_000_000, &[1, 2])?;
//! hand.set_torque(true)?;
//! // The paper's torque limit 400 of 0…1023, closing towards 3.5 rad.
//! let cmd = GripperCommand { position_rad: 3.5, effort: Effort::from_torque_limit_raw(400) };
//! hand.command(&cmd)?; // two sync writes: Goal PWM 346 of 885, Goal Position
//! let state = hand.state()?; // one sync read
//! println!("at {:.2} rad, faults: {}", state.position_rad, state.faults);
//! // A servo that stops answering is a typed error; the broadcast torque-off still reaches it.
//! if let Err(Error::Timeout { id }) = hand.state() {
//!     println!("servo {id:?} does not answer");
//! }
//! hand.safe_stop(SafeAction::TorqueOff)?;
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! To test such code without hardware, the `dxl-sim` crate runs simulated servos that answer
//! Protocol 2.0 on a pseudo-terminal, in a test's process or as a program of their own.
#![deny(unsafe_code)]

pub mod control_table;
mod error;
pub mod grasp_loop;
pub mod protocol;
mod servo_hand;

pub use error::{Error, InstructionError, faults_from_hardware_error};
pub use servo_hand::{
    DEFAULT_REPLY_LATENCY, DecodedAnswer, GoalPackets, PacketCounts, RawGoals, RawServoState,
    ServoHand, decode_replies, encode_goals,
};
