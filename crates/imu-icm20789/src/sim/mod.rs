//! Feature `sim`: a model of the ICM-20789 on the embedded-hal I2C traits, on the stack's one
//! simulated clock ([`SimClock`], the `sim-clock` crate's, re-exported here) with a delay that
//! advances it, and the account of its bus bits ([`BusAccount`]). The driver talks to it
//! exactly as to a chip: the model answers the register map at 0x68 / 0x69 and the barometer
//! command set at 0x63 (behind the bypass), makes pressure codes with the driver's own inverse
//! conversion, honours conversion times against the simulated clock (reads before the end are
//! NACKed) and adds seeded noise.

mod baro_model;
mod bus;
mod chip;
mod environment;
mod imu_model;
mod noise;

pub use bus::{BIT_NS_400KHZ, BusAccount};
pub use chip::{ChipModel, DEFAULT_BARO_ID, DEFAULT_OTP, SimError};
pub use environment::{Environment, TrueState, Truth};
pub use noise::SimNoise;
/// The stack's one simulated clock (the `sim-clock` crate), re-exported: the chip model runs on
/// it, so its users need no other import.
pub use sim_clock::{SimClock, SimDelay};
