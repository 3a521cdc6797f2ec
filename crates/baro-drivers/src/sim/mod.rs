//! Simulation (feature `sim`): an MS5611 chip model speaking the real command set over
//! embedded-hal I2C and SPI and a TCA9548A switch model, on the stack's one simulated clock
//! ([`SimClock`], the `sim-clock` crate's, re-exported here).
//!
//! ```
//! use baro_drivers::sim::{Conditions, Ms5611Sim, SimClock};
//! use baro_drivers::{Address, Ms5611, Osr};
//!
//! let clock = SimClock::new();
//! let air = Conditions { pressure_mbar: 1013.25, temperature_celsius: 21.5 };
//! let chip = Ms5611Sim::new(air, clock.clone()).with_seed(7);
//! let mut delay = clock.delay();
//! let mut baro = Ms5611::new_with_i2c(chip, Address::CsbLow).init(&mut delay).map_err(|e| e.error)?;
//! let m = baro.measure(&mut delay, Osr::Osr4096)?;
//! assert!((m.pressure_mbar() - 1013.25).abs() < 0.1);
//! assert!((m.temperature_celsius() - 21.5).abs() < 0.05);
//! # Ok::<(), baro_drivers::Error<baro_drivers::sim::SimError>>(())
//! ```

mod chip;
mod environment;
mod error;
mod i2c;
mod inverse;
mod mux;
mod spi;
mod timing;

pub use chip::{ConversionTime, DATASHEET_COEFFICIENTS, Ms5611Sim};
pub use environment::{Conditions, Environment};
pub use error::SimError;
pub use i2c::I2cTarget;
pub use mux::Tca9548aSim;
/// The stack's one simulated clock (the `sim-clock` crate), re-exported: the chip models run on
/// it, so their users need no other import.
pub use sim_clock::{SimClock, SimDelay};
pub use timing::BusTiming;
