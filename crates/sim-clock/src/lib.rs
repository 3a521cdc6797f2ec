//! A shared simulated clock for host simulations of embedded code.
//!
//! One nanosecond counter that chip models, their delays and simulation loops share, so a
//! simulation measures time deterministically and never sleeps: a chip model advances it as its
//! bus carries bits and its conversions run, a driver's delay ([`SimDelay`]) advances it instead
//! of sleeping, and a control loop waits on it. Clones share the counter, and it is
//! `Send + Sync`, so a loop on another thread can read and advance the same time as the chips it
//! drives.
//!
//! The clock is an `Arc<AtomicU64>`: it exists where the target has 64-bit atomics (hosts), and
//! the crate is empty elsewhere (a Cortex-M has none), as `alloc::sync` is. The README follows
//! (its example runs as this crate's doctest).
//!
#![doc = include_str!("../README.md")]
#![no_std]
#![forbid(unsafe_code)]

#[cfg(target_has_atomic = "64")]
extern crate alloc;

#[cfg(target_has_atomic = "64")]
mod clock;

#[cfg(target_has_atomic = "64")]
pub use clock::{SimClock, SimDelay};
