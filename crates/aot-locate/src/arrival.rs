//! Arrival-time detection on pressure sample streams, one sample at a time.
//!
//! Each channel tracks its resting pressure with an exponential moving average and declares
//! the contact arrived when the pressure stays `threshold_pa` above that baseline for
//! `debounce` consecutive samples; the arrival time is the first of those samples. The
//! baseline freezes at arrival, so the rise that follows can be read against it.

use crate::geometry::SENSORS;
use crate::score::ArrivalEvent;

/// How a channel decides that the contact has arrived.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DetectorConfig {
    /// Rise above the baseline that counts as contact, Pa. Set it a few times the sensor's
    /// RMS noise (MS5611: 6.5 Pa at OSR 256 … 1.2 Pa at OSR 4096, datasheet).
    pub threshold_pa: f32,
    /// Weight of a new sample in the baseline average, `0.0..=1.0` (1 keeps the last sample).
    pub baseline_alpha: f32,
    /// Consecutive samples above threshold needed; 0 is read as 1.
    pub debounce: u8,
}

impl DetectorConfig {
    /// 30 Pa (0.3 hPa: ≈ 5σ of MS5611 noise at its noisiest OSR), α = 1/8, two samples.
    pub const DEFAULT: DetectorConfig = DetectorConfig {
        threshold_pa: 30.0,
        baseline_alpha: 0.125,
        debounce: 2,
    };
}

impl Default for DetectorConfig {
    /// [`DetectorConfig::DEFAULT`].
    fn default() -> DetectorConfig {
        DetectorConfig::DEFAULT
    }
}

/// One pressure channel's baseline and arrival.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ChannelDetector {
    config: DetectorConfig,
    baseline_pa: Option<f32>,
    run: u8,
    run_start_us: i64,
    arrival_us: Option<i64>,
}

impl ChannelDetector {
    /// A detector with no sample seen yet.
    pub fn new(config: DetectorConfig) -> ChannelDetector {
        ChannelDetector {
            config,
            baseline_pa: None,
            run: 0,
            run_start_us: 0,
            arrival_us: None,
        }
    }

    /// Feeds one sample taken at `t_us`; returns the arrival time once it is known.
    ///
    /// Non-finite samples are skipped (they neither move the baseline nor count towards the
    /// debounce run, and they break a run). The first finite sample seeds the baseline.
    pub fn push(&mut self, t_us: i64, pressure_pa: f32) -> Option<i64> {
        if self.arrival_us.is_some() {
            return self.arrival_us;
        }
        if !pressure_pa.is_finite() {
            self.run = 0;
            return None;
        }
        let Some(base) = self.baseline_pa else {
            self.baseline_pa = Some(pressure_pa);
            return None;
        };
        // f64 so that a rise between extreme f32 values cannot overflow to infinity.
        let rise = f64::from(pressure_pa) - f64::from(base);
        if rise > f64::from(self.config.threshold_pa) {
            if self.run == 0 {
                self.run_start_us = t_us;
            }
            self.run = self.run.saturating_add(1);
            if self.run >= self.config.debounce.max(1) {
                self.arrival_us = Some(self.run_start_us);
            }
        } else {
            self.run = 0;
            // Only resting samples feed the baseline: a rise in progress must not drag it up.
            let a = f64::from(self.config.baseline_alpha.clamp(0.0, 1.0));
            let next = f64::from(base) + a * rise;
            if next.is_finite() {
                self.baseline_pa = Some(next as f32);
            }
        }
        self.arrival_us
    }

    /// The tracked resting pressure, Pa (`None` before the first finite sample).
    pub fn baseline_pa(&self) -> Option<f32> {
        self.baseline_pa
    }

    /// When the contact arrived, in the caller's µs clock.
    pub fn arrival_us(&self) -> Option<i64> {
        self.arrival_us
    }

    /// `pressure_pa` minus the baseline, Pa (0 before the first finite sample).
    pub fn rise_pa(&self, pressure_pa: f32) -> f32 {
        self.baseline_pa.map_or(0.0, |b| pressure_pa - b)
    }

    /// Forgets the arrival and the debounce run (not the baseline): ready for the next tap.
    pub fn rearm(&mut self) {
        self.run = 0;
        self.arrival_us = None;
    }
}

/// Three [`ChannelDetector`]s, one per fingertip sensor.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ArrivalDetector {
    channels: [ChannelDetector; SENSORS],
}

impl ArrivalDetector {
    /// Three channels with the same configuration.
    pub fn new(config: DetectorConfig) -> ArrivalDetector {
        ArrivalDetector {
            channels: [ChannelDetector::new(config); SENSORS],
        }
    }

    /// Feeds one frame of three pressures read at `t_us`.
    pub fn push(&mut self, t_us: i64, pressure_pa: [f32; SENSORS]) {
        for (ch, p) in self.channels.iter_mut().zip(pressure_pa) {
            ch.push(t_us, p);
        }
    }

    /// The per-sensor channels.
    pub fn channels(&self) -> &[ChannelDetector; SENSORS] {
        &self.channels
    }

    /// Whether any sensor has arrived.
    pub fn any_arrived(&self) -> bool {
        self.channels.iter().any(|c| c.arrival_us.is_some())
    }

    /// Forgets every arrival, keeps the baselines.
    pub fn rearm(&mut self) {
        self.channels.iter_mut().for_each(ChannelDetector::rearm);
    }

    /// Streams one frame of a live sensor: when a contact has arrived and every sensor is back
    /// within half the threshold of its baseline (the press is over), forgets the arrivals
    /// first; then feeds the frame. Returns the contact's onset, the earliest arrival, once one
    /// has arrived.
    ///
    /// ```
    /// use aot_locate::{ArrivalDetector, DetectorConfig};
    ///
    /// let mut d = ArrivalDetector::new(DetectorConfig::DEFAULT);
    /// let rest = [101_000.0; 3];
    /// let pressed = [101_400.0, 101_300.0, 101_200.0];
    /// let mut onsets = Vec::new();
    /// for (t, p) in (0..200).map(|i| (i * 1_000, if (50..100).contains(&i) { pressed } else { rest })) {
    ///     onsets.push(d.push_streaming(t, p));
    /// }
    /// assert_eq!(onsets[49], None);
    /// assert!(onsets[99].is_some_and(|t| (50_000..=60_000).contains(&t)));
    /// assert_eq!(onsets[199], None); // released: rearmed
    /// ```
    pub fn push_streaming(&mut self, t_us: i64, pressure_pa: [f32; SENSORS]) -> Option<i64> {
        let at_rest = self
            .channels
            .iter()
            .zip(pressure_pa)
            .all(|(c, p)| c.rise_pa(p) < 0.5 * c.config.threshold_pa);
        if self.any_arrived() && at_rest {
            self.rearm();
        }
        self.push(t_us, pressure_pa);
        self.channels.iter().filter_map(|c| c.arrival_us).min()
    }

    /// The eq. 3 input: `pressure_pa` read against each channel's baseline, and arrival times
    /// counted from `onset_us` (the contact onset on the same clock). An arrival before the
    /// onset counts as 0 µs, one more than `u32::MAX` µs after as `u32::MAX`.
    pub fn event(&self, onset_us: i64, pressure_pa: [f32; SENSORS]) -> ArrivalEvent {
        ArrivalEvent {
            pressure_pa: core::array::from_fn(|k| self.channels[k].rise_pa(pressure_pa[k])),
            arrival_us: core::array::from_fn(|k| {
                self.channels[k]
                    .arrival_us
                    .map(|t| t.saturating_sub(onset_us).clamp(0, i64::from(u32::MAX)) as u32)
            }),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const CFG: DetectorConfig = DetectorConfig {
        threshold_pa: 30.0,
        baseline_alpha: 0.125,
        debounce: 2,
    };

    #[test]
    fn step_arrives_at_its_first_sample() {
        let mut ch = ChannelDetector::new(CFG);
        for i in 0..10 {
            assert_eq!(ch.push(i * 1000, 101_000.0), None);
        }
        assert_eq!(ch.push(10_000, 101_500.0), None); // one sample: debounce holds it back
        assert_eq!(ch.push(11_000, 101_500.0), Some(10_000));
        assert_eq!(ch.baseline_pa(), Some(101_000.0));
        assert_eq!(ch.rise_pa(101_500.0), 500.0);
    }

    #[test]
    fn ramp_arrives_where_it_crosses_the_threshold() {
        // 10 Pa per ms from t = 5 ms: crosses 30 Pa above rest after 3 ms, so the first sample
        // strictly above is at 9 ms (40 Pa).
        let mut ch = ChannelDetector::new(CFG);
        for t in 0..30i64 {
            let p = 100_000.0 + 10.0 * (t - 5).max(0) as f32;
            ch.push(t * 1000, p);
        }
        // The baseline creeps up with the sub-threshold part of the ramp (α = 1/8), which
        // delays the crossing by at most one sample.
        let at = ch.arrival_us().unwrap();
        assert!((9_000..=10_000).contains(&at), "{at}");
    }

    #[test]
    fn noise_below_threshold_never_arrives_and_a_spike_is_debounced() {
        let mut ch = ChannelDetector::new(CFG);
        // Deterministic ±20 Pa noise (a 7-periodic pattern), plus one 200 Pa spike.
        let pattern = [0.0, 20.0, -20.0, 10.0, -10.0, 15.0, -5.0];
        for i in 0..500i64 {
            let spike = if i == 250 { 200.0 } else { 0.0 };
            ch.push(i * 600, 101_000.0 + pattern[(i % 7) as usize] + spike);
        }
        assert_eq!(ch.arrival_us(), None);
        let b = ch.baseline_pa().unwrap();
        assert!((b - 101_000.0).abs() < 20.0, "{b}");
    }

    #[test]
    fn never_arriving_channel_yields_none_in_the_event() {
        let mut d = ArrivalDetector::new(CFG);
        for i in 0..20i64 {
            let p = if i >= 10 { 500.0 } else { 0.0 };
            d.push(i * 1000, [100_000.0 + p, 100_000.0, f32::NAN]);
        }
        let e = d.event(9_000, [100_600.0, 100_000.0, 100_000.0]);
        assert_eq!(e.arrival_us, [Some(1000), None, None]);
        assert_eq!(e.pressure_pa[..2], [600.0, 0.0]);
        // No finite sample on channel 3: no baseline, so no rise.
        assert_eq!(e.pressure_pa[2], 0.0);
        assert!(d.any_arrived());
        d.rearm();
        assert!(!d.any_arrived());
    }

    #[test]
    fn arrival_before_onset_counts_as_zero() {
        let mut d = ArrivalDetector::new(CFG);
        d.push(0, [0.0; 3]);
        d.push(1, [100.0; 3]);
        d.push(2, [100.0; 3]);
        assert_eq!(d.event(50, [0.0; 3]).arrival_us, [Some(0); 3]);
    }
}
