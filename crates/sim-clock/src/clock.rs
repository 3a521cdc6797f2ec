//! The clock and its delay.

use alloc::sync::Arc;
use core::sync::atomic::{AtomicU64, Ordering};

/// A shared simulated clock in nanoseconds since it was made. Clones share the same counter.
///
/// The counter is monotonic and saturates at `u64::MAX` ns (about 584 years) rather than
/// wrapping, so a runaway simulation stops time instead of sending it back to zero.
#[derive(Debug, Clone, Default)]
pub struct SimClock {
    // An atomic rather than a `Cell`: the clock must be `Send` for loops on other threads.
    // Relaxed ordering suffices: the counter is the only state, and it publishes nothing else.
    now_ns: Arc<AtomicU64>,
}

impl SimClock {
    /// A clock at 0 ns.
    pub fn new() -> SimClock {
        SimClock::default()
    }

    /// Now, ns.
    pub fn now_ns(&self) -> u64 {
        self.now_ns.load(Ordering::Relaxed)
    }

    /// Now, µs (rounded down).
    pub fn now_us(&self) -> u64 {
        self.now_ns() / 1_000
    }

    /// Moves time forward by `ns`.
    ///
    /// ```
    /// let clock = sim_clock::SimClock::new();
    /// clock.advance_ns(2_500);
    /// clock.advance_ns(u64::MAX); // saturates
    /// assert_eq!(clock.now_ns(), u64::MAX);
    /// ```
    pub fn advance_ns(&self, ns: u64) {
        // `fetch_update` only fails when the closure returns `None`; this one never does.
        let _ = self
            .now_ns
            .fetch_update(Ordering::Relaxed, Ordering::Relaxed, |t| {
                Some(t.saturating_add(ns))
            });
    }

    /// Moves time forward to `t_ns`; a time not after now changes nothing.
    ///
    /// ```
    /// let clock = sim_clock::SimClock::new();
    /// clock.advance_to_ns(40);
    /// clock.advance_to_ns(10);
    /// assert_eq!(clock.now_ns(), 40);
    /// ```
    pub fn advance_to_ns(&self, t_ns: u64) {
        self.now_ns.fetch_max(t_ns, Ordering::Relaxed);
    }

    /// Runs `f` and returns its result with the simulated time it took, ns.
    pub fn time<T>(&self, f: impl FnOnce() -> T) -> (T, u64) {
        let start = self.now_ns();
        let out = f();
        (out, self.now_ns().saturating_sub(start))
    }

    /// A delay that advances this clock instead of sleeping.
    pub fn delay(&self) -> SimDelay {
        SimDelay::new(self.clone())
    }
}

/// A delay provider (embedded-hal's `DelayNs`; the async one too with feature
/// `embedded-hal-async`) that advances a [`SimClock`] by the time asked for and returns at once.
///
/// ```
/// use sim_clock::{SimClock, SimDelay};
/// use embedded_hal::delay::DelayNs;
///
/// let clock = SimClock::new();
/// let mut delay = SimDelay::new(clock.clone());
/// delay.delay_us(30);
/// assert_eq!(delay.clock().now_ns(), 30_000);
/// assert_eq!(clock.now_ns(), 30_000); // the same time
/// ```
#[derive(Debug, Clone, Default)]
pub struct SimDelay {
    clock: SimClock,
}

impl SimDelay {
    /// A delay on `clock`.
    pub fn new(clock: SimClock) -> SimDelay {
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

#[cfg(feature = "embedded-hal-async")]
impl embedded_hal_async::delay::DelayNs for SimDelay {
    async fn delay_ns(&mut self, ns: u32) {
        self.clock.advance_ns(u64::from(ns));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clones_and_delays_share_one_time() {
        let clock = SimClock::new();
        let other = clock.clone();
        other.advance_ns(7);
        let delay = clock.delay();
        delay.clock().advance_ns(3);
        assert_eq!(clock.now_ns(), 10);
        assert_eq!(other.now_ns(), 10);
        // A fresh clock is another time.
        assert_eq!(SimClock::new().now_ns(), 0);
        assert_eq!(SimDelay::default().clock().now_ns(), 0);
    }

    #[test]
    fn time_is_monotonic_and_saturates() {
        let clock = SimClock::new();
        clock.advance_to_ns(1_999);
        assert_eq!(clock.now_us(), 1);
        clock.advance_to_ns(1_000);
        assert_eq!(clock.now_ns(), 1_999);
        clock.advance_ns(u64::MAX - 1_000);
        clock.advance_ns(5_000);
        assert_eq!(clock.now_ns(), u64::MAX);
        let ((), took) = clock.time(|| clock.advance_ns(1));
        assert_eq!(took, 0);
    }

    #[test]
    fn blocking_and_async_delays_advance_the_clock() {
        use core::future::Future;
        use core::pin::pin;
        use core::task::{Context, Poll, Waker};

        let clock = SimClock::new();
        let mut delay = clock.delay();
        embedded_hal::delay::DelayNs::delay_ms(&mut delay, 2);
        let mut fut = pin!(embedded_hal_async::delay::DelayNs::delay_us(&mut delay, 5));
        // The simulated delay never pends: one poll completes it.
        let polled = fut.as_mut().poll(&mut Context::from_waker(Waker::noop()));
        assert_eq!(polled, Poll::Ready(()));
        assert_eq!(clock.now_ns(), 2_005_000);
    }

    #[test]
    fn a_loop_on_another_thread_shares_the_clock() {
        extern crate std;
        fn send_sync<T: Send + Sync>() {}
        send_sync::<SimClock>();
        send_sync::<SimDelay>();

        let clock = SimClock::new();
        let worker = clock.clone();
        let handle = std::thread::spawn(move || {
            for _ in 0..1_000 {
                worker.advance_ns(1_000);
            }
        });
        for _ in 0..1_000 {
            clock.advance_ns(1);
        }
        handle.join().expect("the worker does not panic");
        // No advance is lost between the threads.
        assert_eq!(clock.now_ns(), 1_001_000);
    }
}
