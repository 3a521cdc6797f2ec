//! A `no_std` driver for the TE / MEAS **MS5611-01BA03** barometer, the pressure sensor of the
//! barometric fingertip (three per finger, six per hand module), built on embedded-hal 1.0.
//!
//! * I2C (address 0x76 / 0x77) and SPI (`SpiDevice`, one chip select per sensor);
//! * blocking [`Ms5611`] and, with feature `async`, `Ms5611Async` / `SchedulerAsync` on
//!   embedded-hal-async, generated from one source;
//! * reset and PROM read with the AN520 CRC-4 check ([`Prom`]): a blank or corrupt PROM is a
//!   typed [`Error`], never a panic;
//! * first- and second-order compensation exactly as the datasheet gives it, in `i64` with
//!   floor shifts ([`Calibration`]);
//! * split-phase conversions (`start_pressure` / `start_temperature` / `read_result`) and a
//!   [`Scheduler`] that samples N sensors in two conversion times instead of 2·N;
//! * feature `sim`: an MS5611 chip model, a TCA9548A switch model and a simulated clock
//!   ([`sim`]), for tests, benches and the hand simulator.
//!
//! # The speed / accuracy knob: OSR
//!
//! | OSR  | conversion typ / max | one D2 + D1 cycle | pressure RMS noise | temperature RMS noise |
//! |------|----------------------|-------------------|--------------------|-----------------------|
//! | 256  | 0.54 / 0.60 ms       | 1.20 ms           | 0.065 mbar         | 0.012 °C              |
//! | 512  | 1.06 / 1.17 ms       | 2.34 ms           | 0.042 mbar         | 0.008 °C              |
//! | 1024 | 2.08 / 2.28 ms       | 4.56 ms           | 0.027 mbar         | 0.005 °C              |
//! | 2048 | 4.13 / 4.54 ms       | 9.08 ms           | 0.018 mbar         | 0.003 °C              |
//! | 4096 | 8.22 / 9.04 ms       | 18.08 ms          | 0.012 mbar         | 0.002 °C              |
//!
//! (MS5611-01BA03 datasheet, pp. 2–3.) The driver always waits the maximum time. With the
//! [`Scheduler`], a cycle over six sensors on 20 MHz SPI takes the "one cycle" column plus
//! 24 µs of transfers; one-by-one [`Ms5611::measure`] calls take six times as long.
//!
//! # Example
//!
//! ```
//! # use baro_drivers::sim::{Conditions, Ms5611Sim, SimClock};
//! use baro_drivers::{Address, Ms5611, Osr};
//! # let clock = SimClock::new();
//! # let i2c = Ms5611Sim::new(Conditions { pressure_mbar: 1000.0, temperature_celsius: 20.0 }, clock.clone());
//! # let mut delay = clock.delay();
//! // `i2c` is any embedded-hal I2C bus, `delay` any DelayNs.
//! let mut baro = Ms5611::new_with_i2c(i2c, Address::CsbLow)
//!     .init(&mut delay)
//!     .map_err(|e| e.error)?; // on failure `e.dev` hands the driver (and the bus) back
//! let m = baro.measure(&mut delay, Osr::Osr1024)?;
//! println!("{:.2} mbar at {:.2} °C", m.pressure_mbar(), m.temperature_celsius());
//! # assert!((m.pressure_mbar() - 1000.0).abs() < 0.2);
//! let _i2c = baro.destroy();
//! # Ok::<(), baro_drivers::Error<baro_drivers::sim::SimError>>(())
//! ```
//!
//! Split phase, for interleaving with other work or other sensors:
//!
//! ```
//! # use baro_drivers::sim::{Conditions, Ms5611Sim, SimClock};
//! use baro_drivers::{Ms5611, Osr};
//! use embedded_hal::delay::DelayNs;
//! # let clock = SimClock::new();
//! # let spi = Ms5611Sim::new(Conditions { pressure_mbar: 850.0, temperature_celsius: 5.0 }, clock.clone());
//! # let mut delay = clock.delay();
//! let mut baro = Ms5611::new_with_spi(spi).init(&mut delay).map_err(|e| e.error)?;
//! baro.start_temperature(Osr::Osr4096)?;
//! delay.delay_ns(Osr::Osr4096.conversion_time_max_ns()); // … or do something useful
//! baro.read_result()?; // D2, kept by the driver
//! baro.start_pressure(Osr::Osr4096)?;
//! delay.delay_ns(Osr::Osr4096.conversion_time_max_ns());
//! let d1 = baro.read_result()?.code;
//! let m = baro.compensate(d1)?;
//! # assert!((m.pressure_mbar() - 850.0).abs() < 0.1);
//! # Ok::<(), baro_drivers::Error<baro_drivers::sim::SimError>>(())
//! ```
//!
//! Many sensors, each on its own chip select (or each behind a TCA9548A channel through the
//! `xca9548a` crate's `split()`):
//!
//! ```
//! # use baro_drivers::sim::{Conditions, Ms5611Sim, SimClock};
//! use baro_drivers::{Measurement, Ms5611, Osr, Scheduler};
//! # let clock = SimClock::new();
//! # let mut delay = clock.delay();
//! # let air = Conditions { pressure_mbar: 1013.0, temperature_celsius: 22.0 };
//! # let chip_selects: Vec<_> = (0..6).map(|i| Ms5611Sim::new(air, clock.clone()).with_seed(i)).collect();
//! let mut fingertips = Vec::new();
//! for spi in chip_selects {
//!     fingertips.push(Ms5611::new_with_spi(spi).init(&mut delay).map_err(|e| e.error)?);
//! }
//! let scheduler = Scheduler::new(Osr::Osr1024);
//! let mut out = [Measurement { temperature_centi_celsius: 0, pressure_pa: 0 }; 6];
//! scheduler.sample_all(&mut fingertips, &mut delay, &mut out).map_err(|e| e.error)?;
//! # assert!(out.iter().all(|m| (m.pressure_mbar() - 1013.0).abs() < 0.2));
//! # Ok::<(), baro_drivers::Error<baro_drivers::sim::SimError>>(())
//! ```
#![no_std]
#![deny(unsafe_code, missing_docs)]

mod command;
mod compensation;
mod error;
mod interface;
mod mode;
mod osr;
mod prom;

pub use compensation::{CODE_MAX, Calibration, CompensationError, Intermediates, Measurement};
pub use error::{Error, ModeChangeError};
#[cfg(feature = "async")]
pub use interface::AsyncTransport;
pub use interface::{Address, I2cInterface, SpiInterface, Transport};
pub use mode::{Ready, Uninit};
pub use osr::Osr;
pub use prom::{Prom, PromError, crc4};
mod driver;
mod scheduler;
pub use command::RESET_TIME_NS;
#[cfg(feature = "async")]
pub use driver::Ms5611Async;
pub use driver::{Channel, Ms5611, RawSample};
#[cfg(feature = "async")]
pub use scheduler::SchedulerAsync;
pub use scheduler::{SampleError, Scheduler};
#[cfg(feature = "sim")]
extern crate std;
#[cfg(feature = "sim")]
pub mod sim;
