//! Fixtures shared by the integration tests.

/// OTP sets for the conversion tests. Synthetic, not read from parts: offsets `c3` near 4 180 put
/// the 80 kPa point near 8.5·2²⁰ LSB, between the fixed 3.5·2²⁰ and 11.5·2²⁰ points (TDK
/// reference `init_base`), and `c0…c2` of ±3 000 give 0…50 Pa per 10 °C, the size of effect the
/// quadratic terms are for. The zero set is the calibration at `t = 0` of any part.
pub(crate) const OTP_SETS: [[i16; 4]; 5] = [
    [1_850, -780, 2_410, 4_174],
    [0, 0, 0, 4_181],
    [-2_000, 1_500, -900, 4_100],
    [3_000, 3_000, 3_000, 4_250],
    [-3_100, -2_900, 700, 4_230],
];

/// Temperature codes whose `t = T_LSB − 32768` is a multiple of 4 096, so `c·t²/2²⁴` is an
/// integer and every LUT point is a whole code (−45 °C … +128 °C, DS-000169 §10 formula).
pub(crate) const WHOLE_CODE_T_LSB: [u16; 6] = [32_768, 28_672, 16_384, 40_960, 4_096, 61_440];

/// Temperature codes where the LUT points fall between codes.
pub(crate) const OTHER_T_LSB: [u16; 4] = [26_214, 30_000, 39_321, 51_234];

/// Runs a future that never waits (the chip model answers at once).
#[cfg(all(feature = "sim", feature = "async"))]
pub(crate) fn block_on<F: core::future::Future>(future: F) -> F::Output {
    let mut future = core::pin::pin!(future);
    let mut cx = core::task::Context::from_waker(core::task::Waker::noop());
    loop {
        if let core::task::Poll::Ready(v) = future.as_mut().poll(&mut cx) {
            return v;
        }
    }
}
