//! One tap as it happens: the press / hold / release profile in time, the realised (jittered)
//! tap, and the pad's true state at any instant — what the chip model measures.

use crate::SimError;
use crate::imu_pad::config::{ImuPadConfig, TapSpec, TapTiming};
use crate::imu_pad::force::ForceDepthCurve;
use crate::imu_pad::grid::TapPosition;
use crate::imu_pad::pattern;
use imu_icm20789::sim::TrueState;
use rand::Rng;
use rand_distr::{Distribution, Normal};

/// Standard gravity, m/s² (the chip lies face up: +g on z at rest).
const GRAVITY: f64 = 9.806_65;

/// The tip's depth profile within a tap, as a fraction of full depth and its normalised rate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Profile {
    /// Rest before the press, s.
    pub lead_s: f64,
    /// Press ramp, s.
    pub press_s: f64,
    /// Hold, s.
    pub hold_s: f64,
    /// Release ramp, s.
    pub release_s: f64,
}

impl From<&TapTiming> for Profile {
    fn from(t: &TapTiming) -> Self {
        Profile {
            lead_s: t.lead_s,
            press_s: t.press_s,
            hold_s: t.hold_s,
            release_s: t.release_s,
        }
    }
}

impl Profile {
    /// `(s, r)` at `t` s into the tap: `s` in 0…1 is the depth fraction (raised-cosine ramps,
    /// the smooth velocity profile of an arm's linear move), `r` in −1…1 is `ds/dt` over its
    /// peak of the current ramp (+ pressing, − releasing). A zero-length ramp is a step with
    /// no rate the chip could sample.
    ///
    /// ```
    /// use hand_sim::imu_pad::tap::Profile;
    /// let p = Profile { lead_s: 0.3, press_s: 0.25, hold_s: 0.6, release_s: 0.25 };
    /// assert_eq!(p.at(0.0), (0.0, 0.0));
    /// assert_eq!(p.at(0.8), (1.0, 0.0));
    /// let (s, r) = p.at(0.3 + 0.125);
    /// assert!((s - 0.5).abs() < 1e-12 && (r - 1.0).abs() < 1e-12);
    /// ```
    pub fn at(&self, t: f64) -> (f64, f64) {
        let ramp = |tau: f64| {
            let x = std::f64::consts::PI * tau;
            (0.5 * (1.0 - x.cos()), x.sin())
        };
        let press_end = self.lead_s + self.press_s;
        let hold_end = press_end + self.hold_s;
        let release_end = hold_end + self.release_s;
        if t.is_nan() || t < self.lead_s || t >= release_end {
            (0.0, 0.0)
        } else if t < press_end {
            ramp((t - self.lead_s) / self.press_s)
        } else if t < hold_end {
            (1.0, 0.0)
        } else {
            let (s, r) = ramp((t - hold_end) / self.release_s);
            (1.0 - s, -r)
        }
    }
}

/// A tap as the simulator realises it: the schedule's values with this repeat's errors.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RealisedTap {
    /// The nominal grid position.
    pub position: TapPosition,
    /// The nominal depth, mm.
    pub nominal_depth_mm: f64,
    /// Depth actually reached, mm (clamped at 0: a negative depth does not touch the pad).
    pub depth_mm: f64,
    /// Actual offset from the chip centre across the pad, mm.
    pub dx_mm: f64,
    /// Actual offset from the chip centre along the pad, mm.
    pub dy_mm: f64,
    /// Actual offset from row 1 along the pad, mm.
    pub y_mm: f64,
    /// Start of this tap's window on the clock, s (the schedule slot plus sample-phase jitter).
    pub start_s: f64,
    /// Peak normal force on the pad, N (the FT-300's reading in the paper).
    pub force_n: f64,
    /// Peak pressure rise, counts.
    pub counts: f64,
    /// Accelerometer x / y during the hold, m/s².
    pub accel_mps2: [f64; 2],
    /// Peak gyroscope x / y rate, rad/s.
    pub gyro_rps: [f64; 2],
}

impl RealisedTap {
    /// Realises `spec` as tap `index` of the schedule, drawing its errors from `rng`.
    pub fn realise(
        spec: &TapSpec,
        index: usize,
        config: &ImuPadConfig,
        curve: &ForceDepthCurve,
        rng: &mut impl Rng,
    ) -> Result<RealisedTap, SimError> {
        let position = spec.position()?;
        let var = &config.variation;
        let mut normal = |sd: f64| {
            Normal::new(0.0, sd)
                .map(|n| n.sample(&mut *rng))
                .unwrap_or(0.0)
        };
        // Always draw the same numbers per tap, whatever the settings, so that changing one
        // spread does not reshuffle the others.
        let (e_depth, e_x, e_y) = (normal(1.0), normal(1.0), normal(1.0));
        let (e_acc, e_gyro) = (normal(1.0), normal(1.0));
        let phase: f64 = rng.random();
        let depth_mm = (spec.depth_mm + var.depth_sd_mm * e_depth).clamp(0.0, 1e3);
        let x_mm = position.x_mm() + var.position_sd_mm * e_x;
        let y_mm = position.y_mm() + var.position_sd_mm * e_y;
        let p = &config.pressure;
        let dx_mm = x_mm;
        let dy_mm = y_mm - (p.chip_row - 1.0) * crate::imu_pad::grid::ROW_STEP_MM;
        let force_n =
            curve.force_n(depth_mm) * pattern::force_factor(&config.mechanics, dx_mm, dy_mm);
        let k = pattern::chip_coupling(p, dx_mm, dy_mm);
        let counts = pattern::pressure_counts(p, depth_mm, k, force_n);
        let tilt = pattern::tilt(dx_mm, dy_mm);
        let gain = |e: f64| (1.0 + var.gain_sd * e).max(0.0);
        // The tilt follows the tap's moment about the chip: force × arm (the arm is in `tilt`).
        let acc = config.motion.accel_mps2_per_n * force_n * gain(e_acc);
        let gyro = config.motion.gyro_rps_per_n * force_n * gain(e_gyro);
        let period_s = 1.0 / config.sample_rate_hz;
        let jitter = if var.onset_jitter {
            phase * period_s
        } else {
            0.0
        };
        Ok(RealisedTap {
            position,
            nominal_depth_mm: spec.depth_mm,
            depth_mm,
            dx_mm,
            dy_mm,
            y_mm,
            start_s: config.timing.start_s + index as f64 * config.timing.tap_s + jitter,
            force_n,
            counts,
            accel_mps2: config
                .motion
                .on_chip(pattern::accel_pattern(tilt).map(|a| a * acc)),
            gyro_rps: config
                .motion
                .on_chip(pattern::gyro_pattern(tilt).map(|g| g * gyro)),
        })
    }
}

/// The pad's truth over time: what [`imu_icm20789::sim::ChipModel`] measures.
#[derive(Debug, Clone)]
pub struct PadTruth {
    taps: Vec<RealisedTap>,
    profile: Profile,
    tap_s: f64,
    start_s: f64,
    ambient_pa: f64,
    pa_per_count: f64,
    temperature_c: f32,
}

impl PadTruth {
    /// The truth for realised `taps` under `config`'s timing and ambient.
    pub fn new(taps: Vec<RealisedTap>, config: &ImuPadConfig) -> Self {
        PadTruth {
            taps,
            profile: Profile::from(&config.timing),
            tap_s: config.timing.tap_s,
            start_s: config.timing.start_s,
            ambient_pa: config.ambient_pa,
            pa_per_count: config.pressure.pa_per_count,
            temperature_c: config.temperature_c,
        }
    }

    /// The realised taps.
    pub fn taps(&self) -> &[RealisedTap] {
        &self.taps
    }

    /// The true state at `t_us` µs.
    pub fn state(&self, t_us: u64) -> TrueState {
        let t = t_us as f64 * 1e-6;
        let mut state = TrueState {
            accel_mps2: [0.0, 0.0, GRAVITY as f32],
            gyro_rps: [0.0; 3],
            pressure_pa: self.ambient_pa,
            temperature_c: self.temperature_c,
        };
        if self.tap_s <= 0.0 || t < self.start_s {
            return state;
        }
        // Only the slot's tap can be active: taps never overlap (validated timing).
        let slot = ((t - self.start_s) / self.tap_s).floor();
        let Some(tap) = self.taps.get(slot as usize).filter(|_| slot < 1e12) else {
            return state;
        };
        let (s, r) = self.profile.at(t - tap.start_s);
        state.accel_mps2[0] = (tap.accel_mps2[0] * s) as f32;
        state.accel_mps2[1] = (tap.accel_mps2[1] * s) as f32;
        state.gyro_rps[0] = (tap.gyro_rps[0] * r) as f32;
        state.gyro_rps[1] = (tap.gyro_rps[1] * r) as f32;
        state.pressure_pa += tap.counts * s * self.pa_per_count;
        state
    }
}
