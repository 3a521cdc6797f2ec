//! MS5611 driver placeholder
#![no_std]
#![deny(unsafe_code, missing_docs)]

mod command;
mod compensation;
mod error;
mod interface;
mod mode;
mod osr;
mod prom;

pub use compensation::{Calibration, CompensationError, Intermediates, Measurement};
pub use error::{Error, ModeChangeError};
pub use interface::{Address, I2cInterface, SpiInterface, Transport};
#[cfg(feature = "async")]
pub use interface::AsyncTransport;
pub use mode::{Ready, Uninit};
pub use osr::Osr;
pub use prom::{Prom, PromError, crc4};
mod driver;
mod scheduler;
pub use command::RESET_TIME_NS;
pub use driver::{Channel, Ms5611, RawSample};
#[cfg(feature = "async")]
pub use driver::Ms5611Async;
pub use scheduler::{SampleError, Scheduler};
#[cfg(feature = "async")]
pub use scheduler::SchedulerAsync;
#[cfg(feature = "sim")]
extern crate std;
#[cfg(feature = "sim")]
pub mod sim;
