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

use std::fmt::Write;

use crate::SimError;
use crate::imu_pad::config::{ImuPadConfig, TapSpec};
use crate::imu_pad::grid::TapPosition;
use crate::imu_pad::model::ImuPad;
use crate::imu_pad::window::{TapWindow, WINDOW_SAMPLES, pressure_peak_pa};
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

/// The CSV header line (without newline).
pub fn csv_header() -> String {
    let mut h = String::from("depth_mm,repeat,column,row,region,force_n,pressure_peak_counts");
    for name in ["ax", "ay", "gx", "gy"] {
        for i in 0..WINDOW_SAMPLES {
            // Writing to a String cannot fail.
            let _ = write!(h, ",{name}_{i:02}");
        }
    }
    h
}

/// `records` as the documented CSV, with a comment block naming `seed`.
///
/// ```
/// use hand_sim::imu_pad::dataset::{to_csv, csv_header};
/// let csv = to_csv(&[], 1);
/// assert!(csv.lines().any(|l| l == csv_header()));
/// ```
pub fn to_csv(records: &[TapRecord], seed: u64) -> String {
    let mut out = format!(
        "# hand-sim imu_pad tap dataset (seed 002 §III-C / §IV-A), seed {seed}.\n\
         # One row per tap; windows are what the imu-icm20789 driver read from the chip model.\n\
         # ax/ay in mm/s^2 (integers), gx/gy in mrad/s (0.1); pressure in counts (1 count = 1 Pa\n\
         # over the tap's rest mean); force_n is the true tap force. Format: hand_sim::imu_pad::dataset.\n"
    );
    out.push_str(&csv_header());
    out.push('\n');
    for r in records {
        let _ = write!(
            out,
            "{:.1},{},{},{},{},{:.3},{:.1}",
            r.depth_mm,
            r.repeat,
            r.position.column(),
            r.position.row(),
            r.position.region(),
            r.force_n,
            r.pressure_peak_counts
        );
        for (s, signal) in r.window.signals.iter().enumerate() {
            for v in signal {
                let _ = if s < 2 {
                    write!(out, ",{}", (f64::from(*v) * 1e3).round() as i64)
                } else {
                    write!(out, ",{:.1}", f64::from(*v) * 1e3)
                };
            }
        }
        out.push('\n');
    }
    out
}
