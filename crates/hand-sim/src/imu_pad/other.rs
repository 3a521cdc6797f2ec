//! Another pad: the same chip and silicone, built by someone else.
//!
//! A hand-made pad is never the paper's: its board is laid out again with the ICM-20789 turned
//! on it and a little up or down the pad, and the silicone's stiffness and the board's mounting
//! set how far a tap tilts it.
//! A contact CNN learns where the chip sat and how much the pad tilted, so the built-in one
//! misplaces taps on such a pad and a user trains their own ([`ImuPadConfig::other_pad`] draws
//! one from a seed for the tests that show both).

use super::ImuPadConfig;
use rand::Rng;

/// How far the chip sits from the paper's (row 13.5), rows: an offset of
/// [`CHIP_SHIFT_MIN_ROWS`] to this, up or down the pad. More would move the rows the pressure
/// trigger sees (§IV-B: rows 7–21 at 1.2 mm): taps at the pad's ends would go unseen.
pub const CHIP_SHIFT_MAX_ROWS: f64 = 1.0;
/// The smallest chip offset, rows.
pub const CHIP_SHIFT_MIN_ROWS: f64 = 0.5;
/// How far the pad's tilt per newton differs from the paper's: the accelerometer's and the
/// gyroscope's amplitudes each scaled by a factor in 1 ± this (a stiffer or softer mounting).
pub const MOTION_SPREAD: f64 = 0.3;

impl ImuPadConfig {
    /// This pad built again, drawn from `seed`: its chip turned one to three quarter turns,
    /// [`CHIP_SHIFT_MIN_ROWS`] to [`CHIP_SHIFT_MAX_ROWS`] rows up or down the pad, its
    /// accelerometer and gyroscope amplitudes each scaled in 1 ± [`MOTION_SPREAD`]. Taps,
    /// timing and the barometer's coupling law are kept.
    ///
    /// ```
    /// use hand_sim::imu_pad::ImuPadConfig;
    /// let base = ImuPadConfig::default();
    /// let a = base.other_pad(1);
    /// assert_eq!(a, base.other_pad(1)); // a seed is one pad
    /// assert_ne!(a, base.other_pad(2));
    /// let shift = (a.pressure.chip_row - base.pressure.chip_row).abs();
    /// assert!((0.5..=1.0).contains(&shift));
    /// assert!((1..=3).contains(&a.motion.chip_quarter_turns));
    /// ```
    pub fn other_pad(&self, seed: u64) -> ImuPadConfig {
        let mut rng = crate::seed::stream(seed, "imu-pad-build");
        let shift = rng.random_range(CHIP_SHIFT_MIN_ROWS..=CHIP_SHIFT_MAX_ROWS);
        let sign = if rng.random::<bool>() { 1.0 } else { -1.0 };
        let mut factor = || 1.0 + MOTION_SPREAD * (2.0 * rng.random::<f64>() - 1.0);
        let (accel, gyro) = (factor(), factor());
        let turns = rng.random_range(1..=3u8);
        let mut pad = self.clone();
        pad.motion.chip_quarter_turns = turns;
        pad.pressure.chip_row += sign * shift;
        pad.motion.accel_mps2_per_n *= accel;
        pad.motion.gyro_rps_per_n *= gyro;
        pad
    }
}
