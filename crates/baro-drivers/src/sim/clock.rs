//! Simulated time: one counter of nanoseconds shared by every chip model and delay on a bus,
//! so tests and benches measure simulated time deterministically, never sleeping.

use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};

/// A shared simulated clock in nanoseconds. Clones share the same counter.
#[derive(Debug, Clone, Default)]
pub struct SimClock {
    now_ns: Arc<AtomicU64>,
}

impl SimClock {
    /// A clock at 0 ns.
    pub fn new() -> Self {
        Self::default()
    }

    /// The current simulated time in nanoseconds.
    pub fn now_ns(&self) -> u64 {
        self.now_ns.load(Ordering::Relaxed)
    }

    /// Moves time forward by `ns`.
    pub fn advance_ns(&self, ns: u64) {
        self.now_ns.fetch_add(ns, Ordering::Relaxed);
    }

    /// Runs `f` and returns its result with the simulated time it took.
    pub fn time<T>(&self, f: impl FnOnce() -> T) -> (T, u64) {
        let start = self.now_ns();
        let out = f();
        (out, self.now_ns() - start)
    }

    /// A delay provider that advances this clock instead of sleeping.
    pub fn delay(&self) -> SimDelay {
        SimDelay {
            clock: self.clone(),
        }
    }
}

/// An embedded-hal `DelayNs` that advances a [`SimClock`].
#[derive(Debug, Clone)]
pub struct SimDelay {
    clock: SimClock,
}

impl embedded_hal::delay::DelayNs for SimDelay {
    fn delay_ns(&mut self, ns: u32) {
        self.clock.advance_ns(u64::from(ns));
    }
}

#[cfg(feature = "async")]
impl embedded_hal_async::delay::DelayNs for SimDelay {
    async fn delay_ns(&mut self, ns: u32) {
        self.clock.advance_ns(u64::from(ns));
    }
}
