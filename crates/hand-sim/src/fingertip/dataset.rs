//! Seeded fingertip datasets for the learning issues, as CSV text.
//!
//! - [`taps`]: every contact shape of seed 000 Figure 7 ([`FIGURE7_SHAPES`], shared with
//!   `aot-locate`) at every position (moved right, then
//!   down, as §4 describes), at 5 / 7 / 9 kgf, two repeats, at every MS5611 OSR: the raw
//!   driver readings around contact onset (for arrival times) and the held pressures (for the
//!   contact-area MLP). Two files: `taps.csv` (one row per tap) and `series.csv` (one row per
//!   frame).
//! - [`weights`]: seed 000 Table 1's experiment — 0 → 200 gf in 10 gf steps on the whole pad,
//!   one step every 2 s, read at OSR 4096 — three seeded runs, one row per frame.

use super::geometry::{Cell, CellSet};
use super::model::{Fingertip, FingertipConfig, TapConfig};
use crate::SimError;
use crate::scene::Model;
use hand_traits::TactileSource;
use std::fmt::Write;

pub use aot_locate::{FIGURE7_SHAPES, Shape};

/// The forces of Figure 9 / Table 2, kgf.
pub const TAP_FORCES_KGF: [f64; 3] = [5.0, 7.0, 9.0];
/// Repeats of each shape, position and force.
pub const TAP_REPEATS: u32 = 2;
/// Every OSR the taps are read at.
pub const TAP_OSRS: [u16; 5] = [256, 512, 1024, 2048, 4096];
/// Contact onset in each tap's run, ns.
const ONSET_NS: u64 = 50_000_000;
/// Series kept around onset: from 30 ms before to 90 ms after, ns.
const WINDOW_NS: (u64, u64) = (30_000_000, 90_000_000);
/// Hold duration, and the late part of it averaged for the held pressures, ns.
const HOLD_NS: u64 = 400_000_000;
const HELD_FROM_NS: u64 = 250_000_000;

/// The tap dataset: (`taps.csv`, `series.csv`).
pub fn taps(seed: u64) -> Result<(String, String), SimError> {
    let mut taps = String::from(
        "# hand-sim fingertip taps (seed 000 Figure 7 shapes x positions x 5/7/9 kgf x repeats x OSR).\n\
         # mask: 24-bit cell set (bit i = cell i, row-major, cell 0 = area 1.1); average_area: eq. 4 label;\n\
         # aot_region: 3 x 3 region (0-8, row-major) of the patch centroid; held*_pa: mean reading over\n\
         # 250-350 ms into the 400 ms hold; onset at t_us = 0 in series.csv.\n\
         tap,osr,shape,size,mask,average_area,aot_region,force_kgf,repeat,held1_pa,held2_pa,held3_pa\n",
    );
    let mut series = String::from(
        "# hand-sim fingertip tap series: every frame from 30 ms before to 90 ms after contact onset,\n\
         # pressures in Pa exactly as the MS5611 driver decoded them; t_us relative to onset.\n\
         tap,t_us,p1_pa,p2_pa,p3_pa\n",
    );
    let mut id = 0u32;
    for osr in TAP_OSRS {
        for shape in FIGURE7_SHAPES {
            for cells in shape.placements() {
                for force_kgf in TAP_FORCES_KGF {
                    for repeat in 0..TAP_REPEATS {
                        let corner = cells
                            .iter()
                            .next()
                            .ok_or_else(|| SimError::config("shape", "empty"))?;
                        let tap = TapConfig {
                            at_s: ONSET_NS as f64 * 1e-9,
                            hold_s: HOLD_NS as f64 * 1e-9,
                            row: corner.row(),
                            col: corner.col(),
                            rows: shape.rows,
                            cols: shape.cols,
                            force_kgf,
                        };
                        let config = FingertipConfig {
                            osr,
                            taps: vec![tap],
                            ..FingertipConfig::default()
                        };
                        let tap_seed = crate::seed::derive(seed, &format!("fingertip/tap/{id}"));
                        let mut tip = Fingertip::new(&config, tap_seed)?;
                        tip.step_to(ONSET_NS + HOLD_NS)?;
                        let mut held = [0.0f64; 3];
                        let mut n = 0.0;
                        for f in tip.frames() {
                            let t_ns = f.t_us * 1000;
                            if t_ns + WINDOW_NS.0 >= ONSET_NS && t_ns <= ONSET_NS + WINDOW_NS.1 {
                                let t_us = f.t_us as i64 - (ONSET_NS / 1000) as i64;
                                let [a, b, c] = f.pressure_pa;
                                writeln!(series, "{id},{t_us},{a},{b},{c}").map_err(fmt_error)?;
                            }
                            if (ONSET_NS + HELD_FROM_NS..=ONSET_NS + HOLD_NS - 50_000_000)
                                .contains(&t_ns)
                            {
                                for (h, p) in held.iter_mut().zip(f.pressure_pa) {
                                    *h += f64::from(p);
                                }
                                n += 1.0;
                            }
                        }
                        let label = cells.average_area().value();
                        let centroid = cells
                            .aot_area()
                            .ok_or_else(|| SimError::config("shape", "empty"))?;
                        writeln!(
                            taps,
                            "{id},{osr},{},{},{},{:.4},{centroid},{force_kgf},{repeat},{:.1},{:.1},{:.1}",
                            shape.name,
                            cells.len(),
                            cells.bits(),
                            label,
                            held[0] / n,
                            held[1] / n,
                            held[2] / n
                        )
                        .map_err(fmt_error)?;
                        id += 1;
                    }
                }
            }
        }
    }
    Ok((taps, series))
}

/// How long each weight of the series is held, ns (Table 1's experiment: one step every 2 s).
pub const WEIGHT_STEP_NS: u64 = 2_000_000_000;
/// Weight added per step, gf.
pub const WEIGHT_STEP_GF: f64 = 10.0;
/// Steps after the unloaded one: 0 → 200 gf.
pub const WEIGHT_STEPS: u32 = 20;

/// The seed of weight-series run `run` of a dataset seeded `seed`.
pub fn weight_run_seed(seed: u64, run: u32) -> u64 {
    crate::seed::derive(seed, &format!("fingertip/weights/{run}"))
}

/// One frame of a weight-series run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WeightReading {
    /// Bus time when the frame was read, µs since the run started.
    pub t_us: u64,
    /// The weight on the pad, gf.
    pub weight_gf: f64,
    /// Sensors 1–3 as the MS5611 driver decoded them, Pa.
    pub pressure_pa: [f32; 3],
}

/// One run of Table 1's experiment on `tip`: 0 gf, then `steps` steps of
/// [`WEIGHT_STEP_GF`] on the whole pad, each held [`WEIGHT_STEP_NS`]; every frame the driver
/// read, in time order. `on_step(step)` is called as each step starts (progress).
pub fn weight_run(
    tip: &mut Fingertip,
    steps: u32,
    mut on_step: impl FnMut(u32),
) -> Result<Vec<WeightReading>, SimError> {
    let all = Cell::all().fold(CellSet::EMPTY, CellSet::with);
    let mut out = Vec::new();
    for step in 0..=steps {
        on_step(step);
        let weight_gf = f64::from(step) * WEIGHT_STEP_GF;
        tip.set_contact(super::ContactPatch::from_kgf(all, weight_gf / 1000.0))?;
        let end = u64::from(step + 1) * WEIGHT_STEP_NS;
        while tip.now_ns() < end {
            let f = tip.read_frame()?;
            out.push(WeightReading {
                t_us: f.t_us,
                weight_gf,
                pressure_pa: f.pressure_pa,
            });
        }
    }
    Ok(out)
}

/// The weight-series dataset (`weights.csv`).
pub fn weights(seed: u64) -> Result<String, SimError> {
    let mut out = String::from(
        "# hand-sim fingertip weight series (seed 000 Table 1's experiment): 0 -> 200 gf in 10 gf steps\n\
         # on the whole pad, one step every 2 s, read at OSR 4096 with 0.1 hPa/min drift; three runs.\n\
         run,t_us,weight_gf,p1_pa,p2_pa,p3_pa\n",
    );
    for run in 0..3u32 {
        let mut tip = Fingertip::new(&FingertipConfig::default(), weight_run_seed(seed, run))?;
        for r in weight_run(&mut tip, WEIGHT_STEPS, |_| {})? {
            let [a, b, c] = r.pressure_pa;
            writeln!(out, "{run},{},{},{a},{b},{c}", r.t_us, r.weight_gf).map_err(fmt_error)?;
        }
    }
    Ok(out)
}

fn fmt_error(_: std::fmt::Error) -> SimError {
    SimError::config("dataset", "formatting failed")
}
