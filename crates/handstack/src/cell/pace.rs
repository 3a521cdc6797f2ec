//! A node loop's period and its stop flag.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
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

/// A shared stop flag: set by a signal, by stdin closing (a node under `cell`), or by a test.
#[derive(Debug, Clone, Default)]
pub struct Stop(Arc<AtomicBool>);

impl Stop {
    /// A flag not set.
    pub fn new() -> Stop {
        Stop::default()
    }

    /// Sets it.
    pub fn set(&self) {
        self.0.store(true, Ordering::Relaxed);
    }

    /// Whether it is set.
    pub fn is_set(&self) -> bool {
        self.0.load(Ordering::Relaxed)
    }

    /// Sets it when stdin reaches its end (the cell closes a node's stdin to stop it).
    pub fn on_stdin_eof(&self) {
        let stop = self.clone();
        std::thread::spawn(move || {
            let mut sink = Vec::new();
            let _ = std::io::Read::read_to_end(&mut std::io::stdin(), &mut sink);
            stop.set();
        });
    }
}
