//! The simulated clock shared by the chip model and its delay, and the bus-time account.

use std::cell::Cell;
use std::rc::Rc;

/// I2C bit time at 400 kHz, ns.
pub const BIT_NS_400KHZ: u64 = 2_500;

#[derive(Debug, Default)]
struct State {
    now_ns: Cell<u64>,
    bus_bits: Cell<u64>,
}

/// Simulated time (ns since the model was made) and the bits the bus carried; clones share it.
#[derive(Debug, Clone, Default)]
pub struct SimClock(Rc<State>);

impl SimClock {
    /// Now, ns.
    pub fn now_ns(&self) -> u64 {
        self.0.now_ns.get()
    }

    /// Now, µs (rounded down).
    pub fn now_us(&self) -> u64 {
        self.now_ns() / 1_000
    }

    /// Moves time forward.
    pub fn advance_ns(&self, ns: u64) {
        self.0.now_ns.set(self.now_ns().saturating_add(ns));
    }

    /// Bits clocked on the bus so far (START, address + ACK, data + ACK, repeated START, STOP).
    pub fn bus_bits(&self) -> u64 {
        self.0.bus_bits.get()
    }

    /// Time the bus has been busy so far at 400 kHz, ns.
    pub fn bus_time_ns(&self) -> u64 {
        self.bus_bits() * BIT_NS_400KHZ
    }

    /// Accounts `bits` of bus traffic and lets the time they take pass.
    pub(crate) fn clock_bits(&self, bits: u64) {
        self.0.bus_bits.set(self.bus_bits() + bits);
        self.advance_ns(bits * BIT_NS_400KHZ);
    }
}

/// A delay that advances the simulated clock instead of sleeping.
#[derive(Debug, Clone, Default)]
pub struct SimDelay {
    clock: SimClock,
}

impl SimDelay {
    /// A delay on `clock`.
    pub fn new(clock: SimClock) -> Self {
        SimDelay { clock }
    }

    /// The clock this delay advances.
    pub fn clock(&self) -> &SimClock {
        &self.clock
    }
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
