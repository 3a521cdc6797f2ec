//! Feature `sim`: a model of the ICM-20789 on the embedded-hal I2C traits, a simulated clock and
//! a delay that advances it. The driver talks to it exactly as to a chip: the model answers
//! the register map at 0x68 / 0x69 and the barometer command set at 0x63 (behind the bypass),
//! makes pressure codes with the driver's own inverse conversion, honours conversion times
//! against the simulated clock (reads before the end are NACKed) and adds seeded noise.

mod baro_model;
mod chip;
mod clock;
mod environment;
mod imu_model;
mod noise;

pub use chip::{ChipModel, DEFAULT_BARO_ID, DEFAULT_OTP, SimError};
pub use clock::{BIT_NS_400KHZ, SimClock, SimDelay};
pub use environment::{Environment, TrueState, Truth};
pub use noise::SimNoise;
