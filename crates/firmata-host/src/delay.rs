//! A blocking delay on the host's clock, for drivers that take an embedded-hal `DelayNs`.

use embedded_hal::delay::DelayNs;

/// `std::thread::sleep` as embedded-hal's `DelayNs`: the delay a chip driver needs beside
/// [`Board`](crate::Board)'s I2C (conversion times, resets). It sleeps at least as long as asked.
///
/// ```
/// use embedded_hal::delay::DelayNs;
/// let start = std::time::Instant::now();
/// firmata_host::StdDelay.delay_ms(2);
/// assert!(start.elapsed() >= std::time::Duration::from_millis(2));
/// ```
#[derive(Debug, Clone, Copy, Default)]
pub struct StdDelay;

impl DelayNs for StdDelay {
    fn delay_ns(&mut self, ns: u32) {
        std::thread::sleep(std::time::Duration::from_nanos(u64::from(ns)));
    }
}
