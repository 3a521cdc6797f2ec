//! The `[imu_pad]` table of a scene: taps, timing, chip mode and the calibrated constants.
//!
//! Every field has a default; the defaults are the paper's figures (seed 002) or the values
//! calibrated to them, each with its source beside it. See `docs/sim-calibration/imu_pad.md`.

use crate::SimError;
use crate::imu_pad::force::{ForceCounts, ForceDepthCurve, Yeoh};
use crate::imu_pad::grid::TapPosition;
use imu_icm20789::BaroMode;
use serde::Deserialize;

/// One scheduled tap: where and how deep.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TapSpec {
    /// Column 1…3.
    pub column: u8,
    /// Row 1…24.
    pub row: u8,
    /// Contact depth, mm (paper: 0.2…1.6, and up to 1.7 at the chip).
    pub depth_mm: f64,
}

impl TapSpec {
    /// The checked grid position.
    pub fn position(&self) -> Result<TapPosition, SimError> {
        TapPosition::new(self.column, self.row)
    }
}

/// When taps happen. Taps run back to back, one every `tap_s` from `start_s`; within a tap
/// the tip rests for `lead_s`, presses over `press_s`, holds `hold_s`, releases over `release_s`.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct TapTiming {
    /// First tap's start, s of simulated time (after the driver's initialisation).
    pub start_s: f64,
    /// One tap's duration, s (§III-C: 3 s per tap).
    pub tap_s: f64,
    /// Rest before the press, s.
    pub lead_s: f64,
    /// Press ramp, s.
    pub press_s: f64,
    /// Hold at full depth, s.
    pub hold_s: f64,
    /// Release ramp, s.
    pub release_s: f64,
}

impl Default for TapTiming {
    /// 3 s per tap (§III-C); the press / hold / release split is a simulation choice (the
    /// paper gives only the duration): a UR3 tap of 0.25 s down, 0.6 s hold, 0.25 s up, so the
    /// whole motion (1.1 s, 33 samples) fits the 38-sample window of §IV-A.
    fn default() -> Self {
        TapTiming {
            start_s: 0.5,
            tap_s: 3.0,
            lead_s: 0.3,
            press_s: 0.25,
            hold_s: 0.6,
            release_s: 0.25,
        }
    }
}

impl TapTiming {
    /// Centre of the motion of tap `index` (middle of the hold), s.
    pub fn centre_s(&self, index: usize) -> f64 {
        self.start_s
            + index as f64 * self.tap_s
            + self.lead_s
            + 0.5 * (self.press_s + self.hold_s + self.release_s)
    }

    fn validate(&self) -> Result<(), SimError> {
        let all = [
            self.start_s,
            self.tap_s,
            self.lead_s,
            self.press_s,
            self.hold_s,
            self.release_s,
        ];
        if !all.iter().all(|v| v.is_finite() && *v >= 0.0 && *v < 1e6) {
            return Err(SimError::config("timing", "every duration finite, 0…1e6 s"));
        }
        let motion = self.lead_s + self.press_s + self.hold_s + self.release_s;
        if motion > self.tap_s {
            return Err(SimError::config(
                "timing.tap_s",
                format!("at least lead + press + hold + release = {motion} s"),
            ));
        }
        Ok(())
    }
}

/// Pad mechanics: the Yeoh law, the fit points and how force falls off towards the edges.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Mechanics {
    /// Yeoh `C1`, kPa (eq. 2: 17).
    pub c1_kpa: f64,
    /// Yeoh `C2`, kPa (eq. 2: −0.2).
    pub c2_kpa: f64,
    /// Yeoh `C3`, kPa (eq. 2: 0.023).
    pub c3_kpa: f64,
    /// Area the stress acts on, mm² (eq. 3: 11.5 × 24 = 276).
    pub area_mm2: f64,
    /// (depth mm, force N) points the Yeoh curve is fitted through (§III-C, Fig. 6B / 7B).
    pub force_points: Vec<[f64; 2]>,
    /// Fraction of the force lost at 12 mm along the pad from the chip (Fig. 4B / 4D: the
    /// edges bend and push back less). Qualitative: the paper gives no numbers.
    pub edge_force_drop: f64,
    /// Force in the side columns relative to the centre one (Fig. 4: centre column highest).
    pub side_column_force: f64,
}

impl Default for Mechanics {
    fn default() -> Self {
        Mechanics {
            c1_kpa: 17.0,
            c2_kpa: -0.2,
            c3_kpa: 0.023,
            area_mm2: 276.0,
            force_points: vec![[0.8, 3.5], [1.3, 8.0], [1.7, 13.0]],
            edge_force_drop: 0.3,
            side_column_force: 0.9,
        }
    }
}

impl Mechanics {
    /// The depth → force curve at the chip, fitted through [`Mechanics::force_points`].
    pub fn curve(&self) -> Result<ForceDepthCurve, SimError> {
        let yeoh = Yeoh {
            c1_kpa: self.c1_kpa,
            c2_kpa: self.c2_kpa,
            c3_kpa: self.c3_kpa,
        };
        ForceDepthCurve::fit(yeoh, self.area_mm2, &self.force_points)
    }

    fn validate(&self) -> Result<(), SimError> {
        if !(0.0..=1.0).contains(&self.edge_force_drop)
            || !(0.0..=1.0).contains(&self.side_column_force)
        {
            return Err(SimError::config(
                "mechanics",
                "edge_force_drop and side_column_force in 0…1",
            ));
        }
        self.curve().map(|_| ())
    }
}

/// How a tap's deflection reaches the barometer, and how force becomes counts.
///
/// Silicone touches the chip when the deflection over it, `d · k(r)`, exceeds `gap_mm`, with
/// `k = 1` within `plateau_mm` of the chip centre and `exp(−((r − plateau) / L)²)` beyond
/// (`L` = `spread_low_mm` towards row 1, `spread_high_mm` towards row 24).
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct PressureCoupling {
    /// Eq. 1 (§III-C), whose inverse gives counts from force.
    pub eq1: ForceCounts,
    /// Pascal per count (see the module docs: a count is 1 Pa above the pre-tap baseline).
    pub pa_per_count: f64,
    /// Deflection over the chip at which silicone touches it, mm.
    pub gap_mm: f64,
    /// Radius around the chip centre with full coupling, mm (half the 4 mm chip, §III-A).
    pub plateau_mm: f64,
    /// Decay length towards row 1, mm.
    pub spread_low_mm: f64,
    /// Decay length towards row 24, mm.
    pub spread_high_mm: f64,
    /// Chip centre along the pad, in rows (§III-C: "positions 13 and 14, where the chip is").
    pub chip_row: f64,
}

impl Default for PressureCoupling {
    /// Calibrated to §III-C: pressure from 0.8 mm, rows 8–19 at 0.8 mm, 4–24 at 1.6 mm.
    /// With the 2 mm plateau, the reach midpoints towards row 1 (6.0 mm at 0.8, 10.0 mm at
    /// 1.6) fix `gap = exp((4 ln 0.8 − ln 1.6) / 3) = 0.635 mm` and `L_low = 4 / √ln(0.8 /
    /// gap) = 8.32 mm`; towards row 24, row 20 out at 0.8 and row 24 in at 1.6 bracket `L_high`
    /// in (8.84, 9.36) mm. Both edges of that bracket sit on the contact contour, so with the
    /// repeat jitter the driver-read peaks are small there; 9.05 mm puts row 24 at 1.6 mm at
    /// ~20 counts and row 20 at 0.8 mm at the ~2-count noise floor.
    fn default() -> Self {
        PressureCoupling {
            eq1: ForceCounts::default(),
            pa_per_count: 1.0,
            gap_mm: 0.635,
            plateau_mm: 2.0,
            spread_low_mm: 8.32,
            spread_high_mm: 9.05,
            chip_row: 13.5,
        }
    }
}

impl PressureCoupling {
    fn validate(&self) -> Result<(), SimError> {
        self.eq1.validate()?;
        let positive = [
            self.pa_per_count,
            self.gap_mm,
            self.spread_low_mm,
            self.spread_high_mm,
        ];
        let ok = positive.iter().all(|v| v.is_finite() && *v > 0.0)
            && self.plateau_mm.is_finite()
            && self.plateau_mm >= 0.0
            && self.chip_row.is_finite();
        if !ok {
            return Err(SimError::config(
                "pressure",
                "pa_per_count, gap_mm, spreads > 0; plateau_mm ≥ 0; all finite",
            ));
        }
        Ok(())
    }
}

/// How big the accelerometer and gyroscope patterns of Fig. 5 are.
///
/// The pad tilts under the tap's moment about the chip, force × arm ([`crate::imu_pad::pattern::tilt`]
/// gives the arm's share), so the amplitudes are per newton of the tap's force (the Yeoh
/// curve times the position's force factor). The paper's Fig. 5 axes are not in its text, so
/// the size is a simulation choice: a 1.6 mm tap on the chip (11.5 N) reads 0.4 m/s² and
/// 64 mrad/s at the pattern's extreme, well above the chip noise (0.02 m/s², 1.5 mrad/s).
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Motion {
    /// Accelerometer x / y during the hold, m/s² per N of tap force at the pattern's extreme.
    pub accel_mps2_per_n: f64,
    /// Peak gyroscope x / y rate during press and release, rad/s per N at the extreme.
    pub gyro_rps_per_n: f64,
    /// Quarter turns of the chip on its board from the paper's mounting (0…3, clockwise seen
    /// from above): a board laid out again reads the same tilt on other axes.
    pub chip_quarter_turns: u8,
}

impl Default for Motion {
    fn default() -> Self {
        Motion {
            // 0.4 m/s² and 0.064 rad/s at 11.52 N (1.6 mm on the chip).
            accel_mps2_per_n: 0.0347,
            gyro_rps_per_n: 0.00555,
            chip_quarter_turns: 0,
        }
    }
}

impl Motion {
    /// A board-frame x / y reading as the turned chip's axes read it: each quarter turn
    /// clockwise, the chip's x axis lies along the board's former y, its y along −x.
    ///
    /// ```
    /// use hand_sim::imu_pad::config::Motion;
    /// let m = Motion { chip_quarter_turns: 1, ..Motion::default() };
    /// assert_eq!(m.on_chip([1.0, 2.0]), [2.0, -1.0]);
    /// assert_eq!(Motion::default().on_chip([1.0, 2.0]), [1.0, 2.0]);
    /// ```
    pub fn on_chip(&self, v: [f64; 2]) -> [f64; 2] {
        (0..self.chip_quarter_turns % 4).fold(v, |[x, y], _| [y, -x])
    }
}

/// Seeded differences between repeats of the same tap.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Variation {
    /// Depth error of the arm, mm rms.
    pub depth_sd_mm: f64,
    /// Position error of the arm (and fabric slip), mm rms per axis.
    pub position_sd_mm: f64,
    /// Relative spread of the IMU amplitudes from tap to tap.
    pub gain_sd: f64,
    /// Start each tap at a random phase of the 30 Hz sample clock.
    pub onset_jitter: bool,
}

impl Default for Variation {
    /// Simulation choices (the paper reports means only): 0.01 mm depth, 0.1 mm position,
    /// 5 % amplitude, random sample phase.
    fn default() -> Self {
        Variation {
            depth_sd_mm: 0.01,
            position_sd_mm: 0.1,
            gain_sd: 0.05,
            onset_jitter: true,
        }
    }
}

/// The ICM-20789 pad model's configuration, the `[imu_pad]` table of a scene.
///
/// ```
/// let scene = hand_sim::scene::SceneConfig::from_toml(r#"
///     seed = 1
///     [imu_pad]
///     taps = [{ column = 2, row = 13, depth_mm = 1.2 }]
///     timing = { tap_s = 3.0 }
/// "#)?;
/// assert_eq!(scene.imu_pad.unwrap().taps.len(), 1);
/// # Ok::<(), hand_sim::SimError>(())
/// ```
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ImuPadConfig {
    /// Taps, in order (default: one 1.2 mm tap on the chip, the real-time depth of §IV-B).
    pub taps: Vec<TapSpec>,
    /// Timing of the taps.
    pub timing: TapTiming,
    /// Frames per second (§III-C: 30 Hz).
    pub sample_rate_hz: f64,
    /// Barometer mode (§III-C: Low Noise).
    pub baro_mode: BaroMode,
    /// Ambient pressure, Pa.
    pub ambient_pa: f64,
    /// Die temperature, °C.
    pub temperature_c: f32,
    /// Pad mechanics.
    pub mechanics: Mechanics,
    /// Deflection → barometer coupling.
    pub pressure: PressureCoupling,
    /// IMU pattern amplitudes.
    pub motion: Motion,
    /// Repeat-to-repeat variation.
    pub variation: Variation,
    /// Most frames one `step_to` may take (a guard against stepping centuries ahead).
    pub max_samples_per_step: u64,
    /// Most frames kept unread; older ones are dropped, as a full FIFO would.
    pub buffer_frames: usize,
}

impl Default for ImuPadConfig {
    fn default() -> Self {
        ImuPadConfig {
            taps: vec![TapSpec {
                column: 2,
                row: 13,
                depth_mm: 1.2,
            }],
            timing: TapTiming::default(),
            sample_rate_hz: 30.0,
            baro_mode: BaroMode::LowNoise,
            ambient_pa: 101_325.0,
            temperature_c: 25.0,
            mechanics: Mechanics::default(),
            pressure: PressureCoupling::default(),
            motion: Motion::default(),
            variation: Variation::default(),
            max_samples_per_step: 1_000_000,
            buffer_frames: 1 << 20,
        }
    }
}

impl ImuPadConfig {
    /// Checks every field; the first problem is a [`SimError::Config`] naming it.
    pub fn validate(&self) -> Result<(), SimError> {
        for tap in &self.taps {
            tap.position()?;
            if !tap.depth_mm.is_finite() {
                return Err(SimError::config("taps.depth_mm", "finite"));
            }
        }
        self.timing.validate()?;
        if !(self.sample_rate_hz.is_finite() && (0.1..=1_000.0).contains(&self.sample_rate_hz)) {
            return Err(SimError::config("sample_rate_hz", "0.1…1000"));
        }
        let period_us = 1e6 / self.sample_rate_hz;
        let conversion_us = f64::from(self.baro_mode.conversion_time_max_us());
        if conversion_us + 2_000.0 > period_us {
            return Err(SimError::config(
                "baro_mode",
                format!(
                    "conversion of {conversion_us} µs plus bus time must fit a frame of {period_us:.0} µs"
                ),
            ));
        }
        if !(self.ambient_pa.is_finite() && (30_000.0..=110_000.0).contains(&self.ambient_pa)) {
            return Err(SimError::config("ambient_pa", "30…110 kPa (§III-A)"));
        }
        if !(self.temperature_c.is_finite() && (-40.0..=85.0).contains(&self.temperature_c)) {
            return Err(SimError::config("temperature_c", "−40…85 °C"));
        }
        self.mechanics.validate()?;
        self.pressure.validate()?;
        let m = [self.motion.accel_mps2_per_n, self.motion.gyro_rps_per_n];
        let v = [
            self.variation.depth_sd_mm,
            self.variation.position_sd_mm,
            self.variation.gain_sd,
        ];
        if !m
            .iter()
            .chain(&v)
            .all(|x| x.is_finite() && *x >= 0.0 && *x < 1e3)
        {
            return Err(SimError::config("motion / variation", "finite, 0…1000"));
        }
        if self.max_samples_per_step == 0 || self.buffer_frames == 0 {
            return Err(SimError::config(
                "max_samples_per_step / buffer_frames",
                "at least 1",
            ));
        }
        Ok(())
    }
}
