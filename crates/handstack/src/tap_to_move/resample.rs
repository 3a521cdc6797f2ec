//! A tap's window at the rate its locator learned: a pad read slower than that (an ICM-20789 in
//! its low-noise mode behind a 115 200-baud Firmata line gives 28.6 frames/s, not 30) would
//! otherwise stretch every window in time, and the contact CNN, trained on 30 Hz windows,
//! misplaces more taps (through such a line the project's test placed 5 of 9 as read, 7 of 9
//! resampled, 8 of 9 read at 30 Hz in the normal mode). The frames are interpolated linearly
//! on the locator's grid, anchored at the trigger.

use hand_traits::ImuFrame;

/// `frames` (in time order, the trigger at index `trigger_at`) resampled at `rate_hz` on a grid
/// through the trigger frame's time: as many frames, as many before the trigger. Each value is
/// interpolated linearly between the frames around its time (held at the ends); the pressure is
/// the nearer frame's. Frames already at `rate_hz` come back as they were.
///
/// ```
/// use hand_traits::ImuFrame;
/// use handstack::tap_to_move::at_rate;
/// // A ramp read at 25 Hz, resampled at 50 Hz around frame 2 (t = 80 ms).
/// let f = |i: u64| ImuFrame { t_us: i * 40_000, accel_mps2: [i as f32, 0.0, 9.8],
///                             gyro_rps: [0.0; 3], pressure_pa: Some(100.0) };
/// let frames: Vec<ImuFrame> = (0..5).map(f).collect();
/// let r = at_rate(&frames, 2, 50.0);
/// let t: Vec<u64> = r.iter().map(|f| f.t_us).collect();
/// assert_eq!(t, [40_000, 60_000, 80_000, 100_000, 120_000]);
/// let a: Vec<f32> = r.iter().map(|f| f.accel_mps2[0]).collect();
/// assert_eq!(a, [1.0, 1.5, 2.0, 2.5, 3.0]);
/// ```
pub fn at_rate(frames: &[ImuFrame], trigger_at: usize, rate_hz: f64) -> Vec<ImuFrame> {
    let Some(anchor) = frames.get(trigger_at) else {
        return frames.to_vec();
    };
    let period_us = 1e6 / rate_hz;
    (0..frames.len())
        .map(|k| {
            let t = anchor.t_us as f64 + (k as f64 - trigger_at as f64) * period_us;
            at_time(frames, t)
        })
        .collect()
}

/// The frame at time `t` µs, interpolated between its neighbours (held at the ends).
fn at_time(frames: &[ImuFrame], t: f64) -> ImuFrame {
    let after = frames.partition_point(|f| (f.t_us as f64) < t);
    let (a, b) = match after {
        0 => (&frames[0], &frames[0]),
        n if n >= frames.len() => (&frames[n - 1], &frames[n - 1]),
        n => (&frames[n - 1], &frames[n]),
    };
    let span = b.t_us.saturating_sub(a.t_us) as f64;
    let w = if span > 0.0 {
        ((t - a.t_us as f64) / span).clamp(0.0, 1.0) as f32
    } else {
        0.0
    };
    let mix = |x: [f32; 3], y: [f32; 3]| core::array::from_fn(|i| x[i] + w * (y[i] - x[i]));
    ImuFrame {
        t_us: t.max(0.0).round() as u64,
        accel_mps2: mix(a.accel_mps2, b.accel_mps2),
        gyro_rps: mix(a.gyro_rps, b.gyro_rps),
        pressure_pa: if w < 0.5 {
            a.pressure_pa
        } else {
            b.pressure_pa
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn frame(t_us: u64, v: f32) -> ImuFrame {
        ImuFrame {
            t_us,
            accel_mps2: [v, -v, 9.8],
            gyro_rps: [2.0 * v, 0.0, 0.0],
            pressure_pa: Some(v),
        }
    }

    #[test]
    fn frames_at_the_rate_come_back_unchanged() {
        let frames: Vec<ImuFrame> = (0..38u64)
            .map(|i| frame(1_000_000 + i * 33_333, (i as f32).sin()))
            .collect();
        let r = at_rate(&frames, 19, 1e6 / 33_333.0);
        for (x, y) in r.iter().zip(&frames) {
            assert_eq!(x.t_us, y.t_us);
            for k in 0..3 {
                assert!((x.accel_mps2[k] - y.accel_mps2[k]).abs() < 1e-5);
                assert!((x.gyro_rps[k] - y.gyro_rps[k]).abs() < 1e-5);
            }
            assert_eq!(x.pressure_pa, y.pressure_pa);
        }
    }

    #[test]
    fn slow_frames_are_interpolated_on_the_grid_and_held_at_the_ends() {
        // 28.6 frames/s (35 ms), a ramp of 1 per ms; resampled at 30 Hz around frame 19.
        let frames: Vec<ImuFrame> = (0..38u64)
            .map(|i| frame(i * 35_000, i as f32 * 35.0))
            .collect();
        let r = at_rate(&frames, 19, 30.0);
        assert_eq!(r.len(), 38);
        assert_eq!(r[19].t_us, 19 * 35_000);
        for f in &r {
            // Inside the frames' span: the ramp's value at the grid time.
            assert!(
                (f.accel_mps2[0] - f.t_us as f32 / 1000.0).abs() < 1e-2,
                "{f:?}"
            );
        }
        // Before the first frame: held.
        let early: Vec<ImuFrame> = (0..5u64)
            .map(|i| frame(100_000 + i * 50_000, i as f32))
            .collect();
        let r = at_rate(&early, 0, 10.0);
        assert_eq!(r[4].accel_mps2[0], 4.0);
        let r = at_rate(&early, 4, 10.0);
        assert_eq!(r[0].accel_mps2[0], 0.0);
    }
}
