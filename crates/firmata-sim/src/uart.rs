//! The serial line as a UART sees it: time on the wire, and what a receiver at another baud
//! rate makes of the bits.

use std::time::Duration;

/// Time `bytes` take on the wire at `baud`, 8N1 (10 bits a byte).
///
/// ```
/// use std::time::Duration;
/// assert_eq!(firmata_sim::uart::wire_time(576, 57_600), Duration::from_millis(100));
/// ```
pub fn wire_time(bytes: usize, baud: u32) -> Duration {
    Duration::from_nanos((bytes as u64 * 10 * 1_000_000_000) / u64::from(baud.max(1)))
}

/// The bytes a UART at `to_baud` receives from `bytes` sent at `from_baud` (8N1): the line is
/// rebuilt bit by bit (idle high, start bit low, 8 data bits LSB first, stop bit high) and
/// sampled as a receiver does — find the falling edge, check the start bit at its middle,
/// sample each data bit at its middle. Equal rates give the bytes back; others give the
/// garbage a board at the wrong baud rate produces.
///
/// ```
/// use firmata_sim::uart::resample;
/// assert_eq!(resample(&[0xF9, 0x02, 0x05], 57_600, 57_600), [0xF9, 0x02, 0x05]);
/// assert_ne!(resample(&[0xF9, 0x02, 0x05], 57_600, 115_200), [0xF9, 0x02, 0x05]);
/// ```
pub fn resample(bytes: &[u8], from_baud: u32, to_baud: u32) -> Vec<u8> {
    let mut bits = Vec::with_capacity(bytes.len() * 10);
    for &b in bytes {
        bits.push(false);
        bits.extend((0..8).map(|k| b & (1 << k) != 0));
        bits.push(true);
    }
    // Time in units of the sender's bits; one receiver bit is `ratio` of them.
    let ratio = f64::from(from_baud) / f64::from(to_baud.max(1));
    let level = |t: f64| -> bool { bits.get(t as usize).copied().unwrap_or(true) };
    let end = bits.len() as f64;
    let mut out = Vec::new();
    let mut t = 0.0;
    while t < end {
        if !level(t) {
            let middle = t + 0.5 * ratio;
            if !level(middle) {
                let byte = (0..8).fold(0u8, |acc, k| {
                    acc | (u8::from(level(middle + f64::from(k + 1) * ratio)) << k)
                });
                out.push(byte);
                // Past the stop bit's middle: the receiver looks for the next start edge.
                t = middle + 9.0 * ratio;
                continue;
            }
        }
        // Receivers sample at 16× their bit rate.
        t += ratio / 16.0;
    }
    out
}
