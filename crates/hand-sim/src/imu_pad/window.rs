//! Cutting one tap out of a frame stream: the 4 × 38 window of §IV-A (accelerometer x / y,
//! gyroscope x / y) and the peak pressure rise over the tap's own baseline.

use crate::SimError;
use hand_traits::ImuFrame;

/// Samples per window (§IV-A: 38).
pub const WINDOW_SAMPLES: usize = 38;
/// Signals per window (§IV-A: acc x, acc y, gyro x, gyro y).
pub const WINDOW_SIGNALS: usize = 4;

/// A 4 × 38 window: rows acc x, acc y (m/s²), gyro x, gyro y (rad/s), as the driver read them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TapWindow {
    /// `signals[s][i]`: signal `s` (acc x, acc y, gyro x, gyro y) at sample `i`.
    pub signals: [[f32; WINDOW_SAMPLES]; WINDOW_SIGNALS],
    /// Time of the first sample, µs.
    pub start_us: u64,
}

impl TapWindow {
    /// The 38 frames around `centre_us`: 19 before the first frame at or after it, 19 from it.
    /// Frames must be in time order; too few on either side is a [`SimError::Config`].
    ///
    /// ```
    /// use hand_sim::imu_pad::TapWindow;
    /// use hand_traits::ImuFrame;
    /// let frames: Vec<ImuFrame> = (0..60_u64)
    ///     .map(|i| ImuFrame { t_us: i * 33_333, accel_mps2: [i as f32, 0.0, 9.8],
    ///                         gyro_rps: [0.0; 3], pressure_pa: None })
    ///     .collect();
    /// let w = TapWindow::extract(&frames, 30 * 33_333)?;
    /// assert_eq!(w.signals[0][0], 11.0);
    /// assert_eq!(w.signals[0][37], 48.0);
    /// assert!(TapWindow::extract(&frames, 50 * 33_333).is_err());
    /// # Ok::<(), hand_sim::SimError>(())
    /// ```
    pub fn extract(frames: &[ImuFrame], centre_us: u64) -> Result<TapWindow, SimError> {
        let half = WINDOW_SAMPLES / 2;
        let centre = frames.partition_point(|f| f.t_us < centre_us);
        let start = centre
            .checked_sub(half)
            .filter(|s| s + WINDOW_SAMPLES <= frames.len())
            .ok_or_else(|| {
                SimError::config(
                    "window",
                    format!("{half} frames needed on each side of {centre_us} µs"),
                )
            })?;
        let slice = &frames[start..start + WINDOW_SAMPLES];
        let mut signals = [[0.0; WINDOW_SAMPLES]; WINDOW_SIGNALS];
        for (i, f) in slice.iter().enumerate() {
            signals[0][i] = f.accel_mps2[0];
            signals[1][i] = f.accel_mps2[1];
            signals[2][i] = f.gyro_rps[0];
            signals[3][i] = f.gyro_rps[1];
        }
        Ok(TapWindow {
            signals,
            start_us: slice[0].t_us,
        })
    }
}

/// Peak pressure rise within `motion_us` (start, end) over the mean of the frames of
/// `slot_us` (start, end) outside it, Pa. Needs pressure frames on both sides of the split.
pub fn pressure_peak_pa(
    frames: &[ImuFrame],
    slot_us: (u64, u64),
    motion_us: (u64, u64),
) -> Result<f64, SimError> {
    let in_slot = frames
        .iter()
        .filter(|f| (slot_us.0..slot_us.1).contains(&f.t_us));
    let (mut sum, mut n, mut peak) = (0.0, 0_u32, f64::NEG_INFINITY);
    for f in in_slot {
        let Some(p) = f.pressure_pa.map(f64::from) else {
            continue;
        };
        if (motion_us.0..motion_us.1).contains(&f.t_us) {
            peak = peak.max(p);
        } else {
            sum += p;
            n += 1;
        }
    }
    if n == 0 || !peak.is_finite() {
        return Err(SimError::config(
            "timing",
            "a tap needs pressure frames at rest and in motion",
        ));
    }
    Ok(peak - sum / f64::from(n))
}
