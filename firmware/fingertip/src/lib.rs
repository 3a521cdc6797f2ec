//! Seed 000's per-fingertip pipeline on the paper's microcontroller class (Cortex-M3, and
//! Cortex-M4F): three MS5611 under the silicone, read by the `baro-drivers` scheduler over any
//! embedded-hal I2C bus; the tared rises into the built-in force DNN; arrival detection,
//! Arrival-of-Time on the 3 × 3 grid and the built-in contact MLP on the 4 × 6 pad; the paper's
//! Mamdani grasp preset for the torque limit; one [`frame`] per cycle to a UART.
//!
//! Everything here is `no_std`. A cycle allocates nothing: the weights are `'static` arrays in
//! flash and every buffer is the pipeline's own. The one heap use is at start-up — the fuzzy
//! engine's term and rule tables, built once by [`Fingertip::new`] (`docs/embedded.md` gives the
//! bytes; the board binary reserves a heap of [`STARTUP_HEAP_BYTES`]).
//!
//! The same code runs on the host against the MS5611 chip model (`examples/host_cycles.rs`),
//! which is how its results and its instruction count per cycle are measured.

#![no_std]
#![forbid(unsafe_code)]

pub mod frame;
mod pipeline;

pub use pipeline::{Config, Error, Estimate, Fingertip, OSR, PAD, SENSORS, SENSORS_MM};

/// Heap the board binary gives the start-up allocations (the fuzzy engine): the host harness
/// measures 4–5 KiB on a 64-bit host, less with 32-bit pointers.
pub const STARTUP_HEAP_BYTES: usize = 40 * 1024;
