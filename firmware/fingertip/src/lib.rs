//! Seed 000's per-fingertip pipeline on the paper's microcontroller class (Cortex-M3, and
//! Cortex-M4F): three MS5611 under the silicone, read by the `baro-drivers` scheduler over any
//! embedded-hal I2C bus; the tared rises into the built-in force DNN; arrival detection,
//! Arrival-of-Time on the 3 × 3 grid and the built-in contact MLP on the 4 × 6 pad; the paper's
//! Mamdani grasp preset for the torque limit; one [`frame`] per cycle to a UART.
//!
//! Everything here is `no_std` and nothing allocates, at start-up or in a cycle: the weights are
//! `'static` arrays in flash, the fuzzy preset's tables fixed-size, and every buffer the
//! pipeline's own. The board binary has no heap (`docs/embedded.md` gives its flash and RAM).
//!
//! The same code runs on the host against the MS5611 chip model (`examples/host_cycles.rs`),
//! which is how its results and its instruction count per cycle are measured.

#![no_std]
#![forbid(unsafe_code)]

pub mod frame;
mod pipeline;

pub use pipeline::{Config, Error, Estimate, Fingertip, OSR, PAD, SENSORS, SENSORS_MM};
