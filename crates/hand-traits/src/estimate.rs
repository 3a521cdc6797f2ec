//! From pad pressures to what a grasp policy sees: the mean contact pressure over a tared
//! zero, its low-pass-filtered rate, and whether the pad is touched. Here, not in
//! `hand-control`, so that a fingertip's firmware (`no_std`) and the host's grasp loop estimate
//! alike.
//!
//! The fuzzy grasp controller of Kim et al. 2020, §5, takes "the difference between the average
//! of the contact pressure values […] and its differential value". A raw difference of two MS5611
//! readings 10 ms apart carries their noise ×√2 / 10 ms (≈ 500 Pa/s at OSR 1024's 3.6 Pa RMS,
//! 5 % of the controller's rate scale), so the rate goes through a first-order low-pass.

use crate::{GraspObservation, PressureFrame};

/// One cycle's estimate.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ContactEstimate {
    /// Mean rise of the sensors over their tared zero, Pa.
    pub pressure_pa: f32,
    /// Filtered time derivative of `pressure_pa`, Pa/s.
    pub rate_pa_per_s: f32,
    /// Whether `pressure_pa` is above the contact threshold.
    pub in_contact: bool,
}

/// Why a frame could not be used.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum EstimateError {
    /// A pressure is NaN or infinite.
    NonFinite {
        /// Index of the sensor in the frame.
        sensor: usize,
    },
    /// The frame's time stamp is not after the previous one.
    TimeNotIncreasing {
        /// This frame's stamp.
        t_us: u64,
        /// The previous frame's stamp.
        previous_us: u64,
    },
    /// An estimate was asked for before the zero was tared.
    NotTared,
}

impl core::fmt::Display for EstimateError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            EstimateError::NonFinite { sensor } => {
                write!(f, "sensor {sensor} read a non-finite pressure")
            }
            EstimateError::TimeNotIncreasing { t_us, previous_us } => write!(
                f,
                "frame at {t_us} µs does not follow the previous one at {previous_us} µs"
            ),
            EstimateError::NotTared => f.write_str("the pad has not been tared"),
        }
    }
}

impl core::error::Error for EstimateError {}

/// Tare, mean rise and filtered rate for an `N`-sensor pad.
///
/// ```
/// use hand_traits::{PressureEstimator, PressureFrame};
///
/// let mut est = PressureEstimator::<3>::new(50.0, 10.0);
/// est.tare(&PressureFrame { t_us: 0, pressure_pa: [101_000.0, 101_010.0, 100_990.0] })?;
/// est.finish_tare()?;
/// let e = est.update(&PressureFrame { t_us: 10_000, pressure_pa: [101_300.0, 101_310.0, 101_290.0] })?;
/// assert!((e.pressure_pa - 300.0).abs() < 1e-3 && e.in_contact);
/// assert_eq!(e.rate_pa_per_s, 0.0); // no rate from a single frame
/// let e = est.update(&PressureFrame { t_us: 20_000, pressure_pa: [101_400.0, 101_410.0, 101_390.0] })?;
/// // 100 Pa in 10 ms is 10 kPa/s raw; the 10 Hz low-pass passes 39 % of it in one step.
/// assert!((e.rate_pa_per_s - 3_858.0).abs() < 10.0, "{e:?}");
/// # Ok::<(), hand_traits::EstimateError>(())
/// ```
#[derive(Debug, Clone)]
pub struct PressureEstimator<const N: usize> {
    contact_threshold_pa: f32,
    tau_s: f32,
    tare_sum: [f64; N],
    tare_count: u32,
    zero_pa: Option<[f64; N]>,
    last: Option<(u64, f32)>,
    rate: f32,
}

impl<const N: usize> PressureEstimator<N> {
    /// An estimator with a contact threshold, Pa, and a rate low-pass cut-off, Hz (> 0).
    pub fn new(contact_threshold_pa: f32, rate_cutoff_hz: f32) -> Self {
        PressureEstimator {
            contact_threshold_pa,
            tau_s: 1.0 / (core::f32::consts::TAU * rate_cutoff_hz),
            tare_sum: [0.0; N],
            tare_count: 0,
            zero_pa: None,
            last: None,
            rate: 0.0,
        }
    }

    /// Adds an untouched frame to the zero being tared.
    pub fn tare(&mut self, frame: &PressureFrame<N>) -> Result<(), EstimateError> {
        check_finite(frame)?;
        for (s, p) in self.tare_sum.iter_mut().zip(frame.pressure_pa) {
            *s += f64::from(p);
        }
        self.tare_count += 1;
        Ok(())
    }

    /// Fixes the zero as the mean of the tared frames.
    pub fn finish_tare(&mut self) -> Result<(), EstimateError> {
        if self.tare_count == 0 {
            return Err(EstimateError::NotTared);
        }
        let n = f64::from(self.tare_count);
        self.zero_pa = Some(self.tare_sum.map(|s| s / n));
        self.last = None;
        self.rate = 0.0;
        Ok(())
    }

    /// Whether the zero is fixed.
    pub fn is_tared(&self) -> bool {
        self.zero_pa.is_some()
    }

    /// Each sensor's tared zero, Pa (`None` before [`finish_tare`](Self::finish_tare)): what a
    /// per-sensor estimator (a force DNN on the three rises) reads its rises against.
    pub fn zero_pa(&self) -> Option<[f64; N]> {
        self.zero_pa
    }

    /// The estimate for `frame`; a bad frame changes nothing.
    pub fn update(&mut self, frame: &PressureFrame<N>) -> Result<ContactEstimate, EstimateError> {
        check_finite(frame)?;
        let zero = self.zero_pa.ok_or(EstimateError::NotTared)?;
        if let Some((previous_us, _)) = self.last {
            if frame.t_us <= previous_us {
                return Err(EstimateError::TimeNotIncreasing {
                    t_us: frame.t_us,
                    previous_us,
                });
            }
        }
        // Subtract in f64: a 3 Pa rise on 101 kPa is below f32's resolution after averaging.
        let rise: f64 = frame
            .pressure_pa
            .iter()
            .zip(zero)
            .map(|(&p, z)| f64::from(p) - z)
            .sum::<f64>()
            / N.max(1) as f64;
        let pressure_pa = rise as f32;
        if let Some((previous_us, previous_pa)) = self.last {
            let dt_s = (frame.t_us - previous_us) as f32 * 1e-6;
            let raw = (pressure_pa - previous_pa) / dt_s;
            let alpha = dt_s / (dt_s + self.tau_s);
            self.rate += alpha * (raw - self.rate);
        }
        self.last = Some((frame.t_us, pressure_pa));
        Ok(ContactEstimate {
            pressure_pa,
            rate_pa_per_s: self.rate,
            in_contact: pressure_pa > self.contact_threshold_pa,
        })
    }
}

impl ContactEstimate {
    /// What the grasp policy sees for a target pressure, Pa.
    pub fn observation(&self, target_pa: f32) -> GraspObservation {
        GraspObservation {
            pressure_error_pa: target_pa - self.pressure_pa,
            pressure_rate_pa_per_s: self.rate_pa_per_s,
        }
    }
}

fn check_finite<const N: usize>(frame: &PressureFrame<N>) -> Result<(), EstimateError> {
    match frame.pressure_pa.iter().position(|p| !p.is_finite()) {
        Some(sensor) => Err(EstimateError::NonFinite { sensor }),
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn frame(t_us: u64, p: f32) -> PressureFrame<3> {
        PressureFrame {
            t_us,
            pressure_pa: [p; 3],
        }
    }

    #[test]
    fn bad_frames_are_typed_errors_and_change_nothing() {
        let mut est = PressureEstimator::<3>::new(50.0, 2.0);
        assert_eq!(est.update(&frame(0, 1e5)), Err(EstimateError::NotTared));
        assert_eq!(est.finish_tare(), Err(EstimateError::NotTared));
        let mut nan = frame(0, 1e5);
        nan.pressure_pa[2] = f32::NAN;
        assert_eq!(est.tare(&nan), Err(EstimateError::NonFinite { sensor: 2 }));
        est.tare(&frame(0, 1e5)).unwrap();
        est.finish_tare().unwrap();
        let first = est.update(&frame(10_000, 1e5 + 200.0)).unwrap();
        // Same or earlier stamp, infinite pressure: refused, and the next good frame's rate is
        // taken against the last good one.
        assert_eq!(
            est.update(&frame(10_000, 1e5 + 300.0)),
            Err(EstimateError::TimeNotIncreasing {
                t_us: 10_000,
                previous_us: 10_000
            })
        );
        let mut inf = frame(20_000, 1e5);
        inf.pressure_pa[0] = f32::INFINITY;
        assert_eq!(
            est.update(&inf),
            Err(EstimateError::NonFinite { sensor: 0 })
        );
        let next = est.update(&frame(20_000, 1e5 + 200.0)).unwrap();
        assert_eq!(first.rate_pa_per_s, 0.0);
        assert_eq!(next.rate_pa_per_s, 0.0);
        assert_eq!(next.pressure_pa, 200.0);
    }

    #[test]
    fn rate_filter_converges_to_a_ramp_slope() {
        // A 1 kPa/s ramp sampled at 100 Hz: the first-order filter's output approaches 1 kPa/s.
        let mut est = PressureEstimator::<3>::new(50.0, 2.0);
        est.tare(&frame(0, 1e5)).unwrap();
        est.finish_tare().unwrap();
        let mut last = ContactEstimate::default();
        for k in 1..=300_u64 {
            last = est
                .update(&frame(k * 10_000, 1e5 + k as f32 * 10.0))
                .unwrap();
        }
        assert!((last.rate_pa_per_s - 1_000.0).abs() < 1.0, "{last:?}");
    }
}
