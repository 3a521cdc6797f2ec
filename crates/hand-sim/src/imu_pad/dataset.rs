//! The seeded tap dataset for the contact-location CNN (seed 002 §IV-A): every grid position
//! at every depth 0.2…1.6 mm, 5 repeats, each tap a 4 × 38 window read through the driver,
//! with its pressure peak and labels.
//!
//! # CSV format
//!
//! Comment lines start with `#`. Then a header and one row per tap, in the order depth,
//! repeat, column, row:
//!
//! | column | meaning |
//! |---|---|
//! | `depth_mm` | nominal contact depth, mm |
//! | `repeat` | 0…4 |
//! | `column`, `row` | grid position, 1…3 and 1…24 |
//! | `region` | §IV-A region 0…8, `3 · ((row − 1) / 8) + column − 1` |
//! | `force_n` | true peak normal force of the tap, N (the FT-300's role; not a chip reading) |
//! | `pressure_peak_counts` | driver-read pressure peak over the tap's rest mean; 1 count = 1 Pa |
//! | `ax_00`…`ax_37`, `ay_00`…`ay_37` | accelerometer x / y, **mm/s²**, integers |
//! | `gx_00`…`gx_37`, `gy_00`…`gy_37` | gyroscope x / y, **mrad/s**, one decimal |
//!
//! The IMU values are the driver's readings (±2 g, ±250 °/s) rounded to a resolution well
//! below the chip model's noise (1 mm/s² vs 20 mm/s²; 0.1 mrad/s vs 1.5 mrad/s rms).

//!
//! A row is one [`ImuTapRow`] ([`Schema`]), which paper-experiments reads back.

use serde::de::{self, Deserializer, SeqAccess, Visitor};
use serde::ser::{SerializeTuple, Serializer};
use serde::{Deserialize, Serialize};
use std::fmt;

use crate::SimError;
use crate::imu_pad::config::{ImuPadConfig, TapSpec};
use crate::imu_pad::grid::TapPosition;
use crate::imu_pad::model::ImuPad;
use crate::imu_pad::window::{TapWindow, WINDOW_SAMPLES, pressure_peak_pa};
use crate::records::{self, Fixed, Schema};
use crate::scene::Model;
use crate::seed;

/// What to generate.
#[derive(Debug, Clone, PartialEq)]
pub struct DatasetSpec {
    /// Root seed; run (depth, repeat) uses `seed::derive(seed, "imu_pad/<µm>/<repeat>")`.
    pub seed: u64,
    /// Nominal depths, mm.
    pub depths_mm: Vec<f64>,
    /// Repeats per depth.
    pub repeats: u32,
    /// Positions tapped in each run, in order.
    pub positions: Vec<TapPosition>,
    /// The pad (its `taps` are replaced by each run's schedule).
    pub pad: ImuPadConfig,
}

impl DatasetSpec {
    /// The paper's collection (§III-C, §IV-A): 72 positions × 0.2, 0.4 … 1.6 mm × 5 repeats.
    pub fn paper(seed: u64) -> DatasetSpec {
        DatasetSpec {
            seed,
            depths_mm: (1..=8).map(|i| f64::from(i) * 0.2).collect(),
            repeats: 5,
            positions: TapPosition::all().collect(),
            pad: ImuPadConfig::default(),
        }
    }
}

/// One tap of the dataset.
#[derive(Debug, Clone, PartialEq)]
pub struct TapRecord {
    /// Nominal depth, mm.
    pub depth_mm: f64,
    /// Repeat index.
    pub repeat: u32,
    /// Grid position.
    pub position: TapPosition,
    /// True peak force, N.
    pub force_n: f64,
    /// Driver-read pressure peak over the rest mean, counts.
    pub pressure_peak_counts: f64,
    /// The 4 × 38 window around the tap.
    pub window: TapWindow,
}

/// Runs one pad per (depth, repeat) over `spec.positions` and cuts every tap out.
pub fn generate(spec: &DatasetSpec) -> Result<Vec<TapRecord>, SimError> {
    let mut records = Vec::with_capacity(spec.depths_mm.len() * spec.positions.len());
    for &depth_mm in &spec.depths_mm {
        for repeat in 0..spec.repeats {
            let mut config = spec.pad.clone();
            config.taps = spec
                .positions
                .iter()
                .map(|p| TapSpec {
                    column: p.column(),
                    row: p.row(),
                    depth_mm,
                })
                .collect();
            let run = format!("imu_pad/{}/{repeat}", (depth_mm * 1000.0).round());
            records.extend(run_taps(&config, seed::derive(spec.seed, &run), repeat)?);
        }
    }
    Ok(records)
}

/// One run: every tap of `config` on a fresh pad seeded with `seed`.
fn run_taps(config: &ImuPadConfig, seed: u64, repeat: u32) -> Result<Vec<TapRecord>, SimError> {
    let mut pad = ImuPad::new(config, seed)?;
    let t = &config.timing;
    let s_to_us = |s: f64| (s * 1e6).round() as u64;
    let end_s = t.start_s + config.taps.len() as f64 * t.tap_s;
    // One frame past the end, so the last window has its 19 frames after the centre.
    pad.step_to(s_to_us(end_s + t.tap_s.min(2.0)) * 1_000)?;
    let frames = pad.drain_frames();
    let period_s = 1.0 / config.sample_rate_hz;
    pad.taps()
        .iter()
        .enumerate()
        .map(|(i, tap)| {
            let slot = t.start_s + i as f64 * t.tap_s;
            let press = slot + t.lead_s;
            // The motion ends one period late at most (sample-phase jitter).
            let release_end = press + t.press_s + t.hold_s + t.release_s + 2.0 * period_s;
            let peak_pa = pressure_peak_pa(
                &frames,
                (s_to_us(slot), s_to_us(slot + t.tap_s)),
                (s_to_us(press), s_to_us(release_end)),
            )?;
            Ok(TapRecord {
                depth_mm: tap.nominal_depth_mm,
                repeat,
                position: tap.position,
                force_n: tap.force_n,
                pressure_peak_counts: peak_pa / config.pressure.pa_per_count,
                window: TapWindow::extract(&frames, s_to_us(t.centre_s(i)))?,
            })
        })
        .collect()
}

/// One row of `taps.csv`: a tap's labels and its window as the file holds them.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ImuTapRow {
    /// Nominal contact depth, mm.
    pub depth_mm: Fixed<f64, 1>,
    /// Repeat 0…4.
    pub repeat: u32,
    /// Grid column 1…3.
    pub column: u8,
    /// Grid row 1…24.
    pub row: u8,
    /// §IV-A region 0…8, `3 · ((row − 1) / 8) + column − 1`.
    pub region: u8,
    /// True peak normal force of the tap, N.
    pub force_n: Fixed<f64, 3>,
    /// Driver-read pressure peak over the rest mean, counts.
    pub pressure_peak_counts: Fixed<f64, 1>,
    /// The window: columns `ax_00`…`ay_37`, then `gx_00`…`gy_37`.
    pub window: WindowRow,
}

impl Schema for ImuTapRow {
    fn columns() -> Vec<String> {
        let mut columns: Vec<String> = [
            "depth_mm",
            "repeat",
            "column",
            "row",
            "region",
            "force_n",
            "pressure_peak_counts",
        ]
        .map(String::from)
        .into();
        for name in SIGNAL_NAMES {
            columns.extend((0..WINDOW_SAMPLES).map(|i| format!("{name}_{i:02}")));
        }
        columns
    }
}

/// The window's signals as the file names them, in column order.
pub const SIGNAL_NAMES: [&str; 4] = ["ax", "ay", "gx", "gy"];

/// A tap's 4 × 38 window as written: the accelerometer in whole mm/s², the gyroscope in
/// mrad/s to 0.1 — resolutions well below the chip model's noise (20 mm/s², 1.5 mrad/s rms).
#[derive(Debug, Clone, PartialEq)]
pub struct WindowRow {
    /// Acceleration x, then y, mm/s².
    pub accel_mm_s2: [[i64; WINDOW_SAMPLES]; 2],
    /// Angular rate x, then y, mrad/s.
    pub gyro_mrad_s: [[Fixed<f64, 1>; WINDOW_SAMPLES]; 2],
}

impl WindowRow {
    /// The window of `w` (driver units: m/s², rad/s) at the file's resolution.
    pub fn new(w: &TapWindow) -> Self {
        let [ax, ay, gx, gy] = &w.signals;
        let accel = |s: &[f32; WINDOW_SAMPLES]| s.map(|v| (f64::from(v) * 1e3).round() as i64);
        let gyro = |s: &[f32; WINDOW_SAMPLES]| s.map(|v| Fixed(f64::from(v) * 1e3));
        WindowRow {
            accel_mm_s2: [accel(ax), accel(ay)],
            gyro_mrad_s: [gyro(gx), gyro(gy)],
        }
    }

    /// The four signals in the file's units (mm/s², mrad/s), channel-major: ax, ay, gx, gy.
    pub fn signals(&self) -> [[f64; WINDOW_SAMPLES]; 4] {
        let [ax, ay] = self.accel_mm_s2.map(|s| s.map(|v| v as f64));
        let [gx, gy] = self.gyro_mrad_s.map(|s| s.map(|v| v.0));
        [ax, ay, gx, gy]
    }
}

/// Values in a row: 2 × 38 accelerometer, then 2 × 38 gyroscope.
const WINDOW_VALUES: usize = 4 * WINDOW_SAMPLES;

impl Serialize for WindowRow {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut t = s.serialize_tuple(WINDOW_VALUES)?;
        for v in self.accel_mm_s2.iter().flatten() {
            t.serialize_element(v)?;
        }
        for v in self.gyro_mrad_s.iter().flatten() {
            t.serialize_element(v)?;
        }
        t.end()
    }
}

impl<'de> Deserialize<'de> for WindowRow {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct Values;
        impl<'de> Visitor<'de> for Values {
            type Value = WindowRow;

            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                write!(f, "{WINDOW_VALUES} window values")
            }

            fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<WindowRow, A::Error> {
                let mut w = WindowRow {
                    accel_mm_s2: [[0; WINDOW_SAMPLES]; 2],
                    gyro_mrad_s: [[Fixed(0.0); WINDOW_SAMPLES]; 2],
                };
                let mut n = 0;
                for v in w.accel_mm_s2.iter_mut().flatten() {
                    *v = Self::next(&mut seq, &mut n)?;
                }
                for v in w.gyro_mrad_s.iter_mut().flatten() {
                    *v = Self::next(&mut seq, &mut n)?;
                }
                Ok(w)
            }
        }
        impl Values {
            /// Element `n` of `seq` (counted on), or an error saying how many there were.
            fn next<'de, A: SeqAccess<'de>, T: Deserialize<'de>>(
                seq: &mut A,
                n: &mut usize,
            ) -> Result<T, A::Error> {
                *n += 1;
                seq.next_element()?
                    .ok_or_else(|| de::Error::invalid_length(*n - 1, &Values))
            }
        }
        d.deserialize_tuple(WINDOW_VALUES, Values)
    }
}

impl ImuTapRow {
    /// The row of `r`.
    pub fn new(r: &TapRecord) -> Self {
        ImuTapRow {
            depth_mm: Fixed(r.depth_mm),
            repeat: r.repeat,
            column: r.position.column(),
            row: r.position.row(),
            region: r.position.region(),
            force_n: Fixed(r.force_n),
            pressure_peak_counts: Fixed(r.pressure_peak_counts),
            window: WindowRow::new(&r.window),
        }
    }
}

/// The CSV header line (without newline).
pub fn csv_header() -> String {
    ImuTapRow::columns().join(",")
}

/// The `#` lines of a dataset seeded `seed`.
pub fn preamble(seed: u64) -> String {
    format!(
        "# hand-sim imu_pad tap dataset (seed 002 §III-C / §IV-A), seed {seed}.\n\
         # One row per tap; windows are what the imu-icm20789 driver read from the chip model.\n\
         # ax/ay in mm/s^2 (integers), gx/gy in mrad/s (0.1); pressure in counts (1 count = 1 Pa\n\
         # over the tap's rest mean); force_n is the true tap force. Format: hand_sim::imu_pad::dataset.\n"
    )
}

/// `records` as the documented CSV, with a comment block naming `seed`.
///
/// ```
/// use hand_sim::imu_pad::dataset::{to_csv, csv_header};
/// let csv = to_csv(&[], 1);
/// assert!(csv.lines().any(|l| l == csv_header()));
/// ```
pub fn to_csv(records: &[TapRecord], seed: u64) -> String {
    records::render(&preamble(seed), records.iter().map(ImuTapRow::new))
}
