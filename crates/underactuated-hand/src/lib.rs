//! A tendon-driven underactuated four-finger hand on an Arduino over Firmata: the hand of the
//! underactuated-hand softness paper ("Distinguish the Textures of Grasped Objects…", §2): one
//! stepper closes all four fingers through a seesaw differential, each finger's distal phalanx
//! carries a force-sensing resistor and its distal joint a potentiometer, and an Arduino reads
//! the eight sensors as analog voltages.
//!
//! - [`Wiring`]: which analog channel is which sensor, the stepper's device and pins;
//!   [`Drive`]: steps to tendon;
//! - [`calibration`]: ADC counts to newtons (the FSR divider's power law) and degrees (the
//!   potentiometer's linear travel);
//! - [`grasp`]: the paper's recording, first contact t₁ to t₁ + 14 s at a fixed rate;
//! - [`UnderactuatedHand`] (feature `firmata`, on by default): the hand on a board running
//!   ConfigurableFirmata with AccelStepperFirmata, through `firmata-host`.
//!
//! ```no_run
//! use underactuated_hand::grasp::{GraspPlan, Phase, Recorder};
//! use underactuated_hand::{HandConfig, UnderactuatedHand};
//! use std::time::Duration;
//!
//! let plan = GraspPlan::default(); // 1.5 mm/s, 14 s at 10 Hz from first contact
//! let mut hand = UnderactuatedHand::open("/dev/ttyACM0", &HandConfig::default())?;
//! let mut rec = Recorder::new(plan, 0);
//! hand.close_at(plan.closing_speed_mm_s)?;
//! while !matches!(rec.phase(), Phase::Done | Phase::Empty) {
//!     if let Some(r) = hand.next_reading(Duration::from_millis(100))? {
//!         rec.push(r.t_us, r.sample);
//!     }
//! }
//! hand.stop()?; // t₂: the actuator holds
//! println!("{} samples from first contact", rec.series().len() / 8);
//! # Ok::<(), underactuated_hand::HandError>(())
//! ```
#![deny(unsafe_code)]

pub mod calibration;
pub mod grasp;
mod wiring;

#[cfg(feature = "firmata")]
mod error;
#[cfg(feature = "firmata")]
mod hand;

pub use calibration::Calibration;
#[cfg(feature = "firmata")]
pub use error::HandError;
#[cfg(feature = "firmata")]
pub use hand::{HandConfig, LEASE, Reading, UnderactuatedHand};
pub use wiring::{Drive, Wiring};
