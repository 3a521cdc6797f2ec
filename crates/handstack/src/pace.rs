//! A loop's period (a node's, a pad read at its frame rate).

use std::time::{Duration, Instant};

/// Keeps a loop at a rate: each [`wait`](Pacer::wait) sleeps until the next tick (a tick missed
/// is not made up: the next one counts from now).
#[derive(Debug)]
pub struct Pacer {
    period: Duration,
    next: Instant,
}

impl Pacer {
    /// Ticks at `rate_hz` (at most 10 kHz, at least one a minute).
    pub fn new(rate_hz: f64) -> Pacer {
        let hz = if rate_hz.is_finite() {
            rate_hz.clamp(1.0 / 60.0, 1e4)
        } else {
            1.0
        };
        Pacer {
            period: Duration::from_secs_f64(1.0 / hz),
            next: Instant::now(),
        }
    }

    /// Sleeps until the next tick.
    pub fn wait(&mut self) {
        self.next += self.period;
        let now = Instant::now();
        match self.next.checked_duration_since(now) {
            Some(left) => std::thread::sleep(left),
            None => self.next = now,
        }
    }
}
