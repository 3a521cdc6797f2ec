//! The loop's time base and its fixed-rate scheduler.
//!
//! A clock is a trait so the same loop runs on wall time ([`StdClock`]) and on a simulator's
//! clock, where "waiting" advances the simulated physics (tests: a 120 s hold in well under a
//! second of CPU).

/// A monotonic clock the loop can wait on.
pub trait LoopClock {
    /// Now, µs since the clock's epoch.
    fn now_us(&mut self) -> u64;
    /// Returns at `t_us` or later. A simulated clock advances its world to `t_us`.
    fn wait_until_us(&mut self, t_us: u64);
}

/// A boxed clock is a clock: a stack that picks its clock at run time (hardware or simulated)
/// hands the loop a `Box<dyn LoopClock>`.
impl<C: LoopClock + ?Sized> LoopClock for Box<C> {
    fn now_us(&mut self) -> u64 {
        (**self).now_us()
    }

    fn wait_until_us(&mut self, t_us: u64) {
        (**self).wait_until_us(t_us);
    }
}

/// Wall time from [`std::time::Instant`], waiting by sleeping.
#[derive(Debug, Clone, Copy)]
pub struct StdClock {
    epoch: std::time::Instant,
}

impl StdClock {
    /// A clock whose epoch is now.
    pub fn new() -> StdClock {
        StdClock {
            epoch: std::time::Instant::now(),
        }
    }
}

impl Default for StdClock {
    fn default() -> Self {
        StdClock::new()
    }
}

impl LoopClock for StdClock {
    fn now_us(&mut self) -> u64 {
        u64::try_from(self.epoch.elapsed().as_micros()).unwrap_or(u64::MAX)
    }

    fn wait_until_us(&mut self, t_us: u64) {
        let now = self.now_us();
        if t_us > now {
            std::thread::sleep(std::time::Duration::from_micros(t_us - now));
        }
    }
}

/// The `sim-clock` crate's simulated clock (feature `sim-clock`), on which waiting is
/// advancing: the loop runs on the same time as the simulated chips that share the clock (the
/// MS5611 and ICM-20789 chip models run on it), as fast as the CPU allows. Another thread
/// holding a clone sees the loop's time.
///
/// ```
/// use hand_control::grasp_loop::{FixedRate, LoopClock};
/// use sim_clock::SimClock;
///
/// let mut clock = SimClock::new();
/// let chip = clock.clone(); // e.g. given to a chip model
/// let mut rate = FixedRate::new(10_000, 0);
/// for _ in 0..3 {
///     rate.wait(&mut clock);
/// }
/// assert_eq!(chip.now_us(), 20_000);
/// ```
#[cfg(feature = "sim-clock")]
impl LoopClock for sim_clock::SimClock {
    fn now_us(&mut self) -> u64 {
        // The inherent method (path resolution prefers it over this trait's).
        sim_clock::SimClock::now_us(self)
    }

    fn wait_until_us(&mut self, t_us: u64) {
        self.advance_to_ns(t_us.saturating_mul(1_000));
    }
}

/// Ticks every `period_us` on a fixed grid: a late cycle does not shift later ticks, and ticks
/// missed while a cycle overran are skipped (and counted) rather than run back to back.
///
/// ```
/// use hand_control::grasp_loop::{FixedRate, LoopClock};
///
/// /// A clock that jumps to wherever it is asked to wait.
/// struct Jump(u64);
/// impl LoopClock for Jump {
///     fn now_us(&mut self) -> u64 { self.0 }
///     fn wait_until_us(&mut self, t: u64) { self.0 = self.0.max(t); }
/// }
///
/// let mut clock = Jump(0);
/// let mut rate = FixedRate::new(10_000, 0);
/// assert_eq!(rate.wait(&mut clock), 0);
/// assert_eq!(rate.wait(&mut clock), 10_000);
/// clock.0 = 35_000; // a cycle overran by 2.5 periods
/// assert_eq!(rate.wait(&mut clock), 40_000);
/// assert_eq!(rate.missed_ticks(), 2);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FixedRate {
    period_us: u64,
    next_us: u64,
    missed: u64,
}

impl FixedRate {
    /// Ticks at `start_us`, `start_us + period_us`, …; a zero period is taken as 1 µs.
    pub fn new(period_us: u64, start_us: u64) -> FixedRate {
        FixedRate {
            period_us: period_us.max(1),
            next_us: start_us,
            missed: 0,
        }
    }

    /// The tick [`wait`](Self::wait) would return if called at `now_us`, and how many ticks
    /// it would skip.
    pub fn peek(&self, now_us: u64) -> (u64, u64) {
        if now_us > self.next_us {
            // Overran: the first grid tick not in the past.
            let behind = (now_us - self.next_us).div_ceil(self.period_us);
            (self.next_us + behind * self.period_us, behind)
        } else {
            (self.next_us, 0)
        }
    }

    /// Waits for the next tick on the grid and returns its scheduled time, µs.
    pub fn wait(&mut self, clock: &mut impl LoopClock) -> u64 {
        let (tick, skipped) = self.peek(clock.now_us());
        self.missed += skipped;
        clock.wait_until_us(tick);
        self.next_us = tick + self.period_us;
        tick
    }

    /// Ticks skipped because a cycle overran.
    pub fn missed_ticks(&self) -> u64 {
        self.missed
    }

    /// The period, µs.
    pub fn period_us(&self) -> u64 {
        self.period_us
    }
}

#[cfg(all(test, feature = "sim-clock"))]
mod tests {
    use super::*;
    use sim_clock::SimClock;

    #[test]
    fn the_simulated_clock_waits_by_advancing_and_never_goes_back() {
        let mut clock = SimClock::new();
        clock.advance_ns(1_500);
        assert_eq!(LoopClock::now_us(&mut clock), 1);
        clock.wait_until_us(40);
        assert_eq!(clock.now_ns(), 40_000);
        clock.wait_until_us(10); // in the past: no change
        assert_eq!(clock.now_ns(), 40_000);
        clock.wait_until_us(u64::MAX); // saturates rather than wrapping to a past time
        assert_eq!(clock.now_ns(), u64::MAX);
    }

    #[test]
    fn a_fixed_rate_loop_on_another_thread_shares_the_time() {
        let clock = SimClock::new();
        let mut looped = clock.clone();
        let ticks = std::thread::spawn(move || {
            let mut rate = FixedRate::new(10_000, 0);
            (0..5).map(|_| rate.wait(&mut looped)).collect::<Vec<_>>()
        })
        .join()
        .expect("the loop does not panic");
        assert_eq!(ticks, [0, 10_000, 20_000, 30_000, 40_000]);
        assert_eq!(clock.now_us(), 40_000);
        // Overran: at 75 ms, a loop due at 50 ms skips the ticks at 50, 60 and 70 ms.
        let mut clock = clock;
        let mut rate = FixedRate::new(10_000, 50_000);
        clock.advance_ns(35_000_000);
        assert_eq!(rate.wait(&mut clock), 80_000);
        assert_eq!(rate.missed_ticks(), 3);
    }
}
