//! Weight datasets for the force DNN (seed 000 §2.2): three fingertip pressures → the weight
//! resting on the pad.
//!
//! Every sample is *tared*: its inputs are the pressure rises above the sensors' own unloaded
//! reading, in hPa (the paper's three sensors rest at 1191, 1199 and 1018 hPa, the simulated
//! ones near 1010 hPa with a different offset every power-up; the weight is in the rise).
//!
//! - Table 1 ([`tared_table`]): 13 rows as printed; the tare is the 0 gf row.
//! - The hand-sim series (`fixtures/datasets/fingertip/weights.csv`, [`parse_series`]): three
//!   runs of 0 → 200 gf in 10 gf steps held 2 s each, read at OSR 4096 every ~18 ms with the
//!   sensors drifting 0.1 hPa/min. Each run's tare is the mean of its first [`TARE_US`] µs
//!   (nothing on the pad yet), as a scale zeroes itself at power-up.

use crate::data::fingertip::{data_lines, field};
use std::path::{Path, PathBuf};
use tactile_nets::error::NetError;

/// Length of the unloaded window at the start of a run that sets its tare, µs.
pub const TARE_US: i64 = 1_000_000;
/// How long a weight is held in the simulated series, µs.
pub const STEP_US: i64 = 2_000_000;
/// The settled part of a step that a step average reads: its last second, µs.
pub const SETTLED_US: i64 = 1_000_000;

pub use tactile_nets::force_dnn::{WeightSample, tared_table};

/// One frame of `weights.csv`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WeightFrame {
    /// Run index (0, 1, 2).
    pub run: u32,
    /// Time since the run started, µs.
    pub t_us: i64,
    /// The weight on the pad, gf.
    pub weight_gf: f32,
    /// Sensors 1–3, Pa.
    pub pressure_pa: [f32; 3],
}

/// `weights.csv` below the workspace root `root`.
pub fn series_path(root: &Path) -> PathBuf {
    root.join("fixtures/datasets/fingertip/weights.csv")
}

/// Reads the committed weight series below the workspace root `root`.
pub fn load_series(root: &Path) -> Result<Vec<WeightFrame>, NetError> {
    parse_series(&std::fs::read_to_string(series_path(root))?)
}

/// Parses `weights.csv` (`run,t_us,weight_gf,p1_pa,p2_pa,p3_pa`).
pub fn parse_series(text: &str) -> Result<Vec<WeightFrame>, NetError> {
    data_lines(text, "run,")
        .map(|(line, l)| {
            let f: Vec<&str> = l.split(',').collect();
            if f.len() != 6 {
                return Err(NetError::Data {
                    line,
                    reason: format!("{} fields, expected 6", f.len()),
                });
            }
            Ok(WeightFrame {
                run: field(&f, 0, "run", line)?,
                t_us: field(&f, 1, "t_us", line)?,
                weight_gf: field(&f, 2, "weight_gf", line)?,
                pressure_pa: [
                    field(&f, 3, "p1_pa", line)?,
                    field(&f, 4, "p2_pa", line)?,
                    field(&f, 5, "p3_pa", line)?,
                ],
            })
        })
        .collect()
}

/// The runs present in `frames`, ascending.
pub fn runs(frames: &[WeightFrame]) -> Vec<u32> {
    let mut v: Vec<u32> = frames.iter().map(|f| f.run).collect();
    v.sort_unstable();
    v.dedup();
    v
}

/// Mean pressure of `run`'s first [`TARE_US`] µs, Pa.
///
/// Errors: [`NetError::Data`] when the run has no frame in that window or it is loaded.
pub fn tare_pa(frames: &[WeightFrame], run: u32) -> Result<[f64; 3], NetError> {
    let window: Vec<&WeightFrame> = frames
        .iter()
        .filter(|f| f.run == run && f.t_us < TARE_US)
        .collect();
    if window.is_empty() || window.iter().any(|f| f.weight_gf != 0.0) {
        return Err(NetError::Data {
            line: 0,
            reason: format!("run {run} has no unloaded frames in its first {TARE_US} µs"),
        });
    }
    let n = window.len() as f64;
    Ok(core::array::from_fn(|k| {
        window
            .iter()
            .map(|f| f64::from(f.pressure_pa[k]))
            .sum::<f64>()
            / n
    }))
}

/// Every frame of `run` as a tared sample (rises in hPa), in time order.
pub fn frame_samples(frames: &[WeightFrame], run: u32) -> Result<Vec<WeightSample>, NetError> {
    let tare = tare_pa(frames, run)?;
    Ok(frames
        .iter()
        .filter(|f| f.run == run)
        .map(|f| WeightSample {
            rise_hpa: core::array::from_fn(|k| {
                ((f64::from(f.pressure_pa[k]) - tare[k]) / 100.0) as f32
            }),
            weight_gf: f.weight_gf,
        })
        .collect())
}

/// One sample per weight step of `run`: the mean tared rise over the step's settled last
/// [`SETTLED_US`] µs (the paper's "average measured values" of Table 1).
pub fn step_samples(frames: &[WeightFrame], run: u32) -> Result<Vec<WeightSample>, NetError> {
    let tare = tare_pa(frames, run)?;
    let mut steps: Vec<(i64, [f64; 3], usize, f32)> = Vec::new();
    for f in frames.iter().filter(|f| f.run == run) {
        let step = f.t_us.div_euclid(STEP_US);
        if f.t_us - step * STEP_US < STEP_US - SETTLED_US {
            continue;
        }
        if steps.last().is_none_or(|s| s.0 != step) {
            steps.push((step, [0.0; 3], 0, f.weight_gf));
        }
        if let Some(s) = steps.last_mut() {
            for ((sum, p), t) in s.1.iter_mut().zip(f.pressure_pa).zip(tare) {
                *sum += f64::from(p) - t;
            }
            s.2 += 1;
        }
    }
    Ok(steps
        .into_iter()
        .map(|(_, sum, n, weight_gf)| WeightSample {
            rise_hpa: core::array::from_fn(|k| (sum[k] / n as f64 / 100.0) as f32),
            weight_gf,
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    const SERIES: &str = "# comment\nrun,t_us,weight_gf,p1_pa,p2_pa,p3_pa\n\
        0,100,0,1000,2000,3000\n0,900000,0,1002,2000,3000\n\
        0,1500000,0,1001,2000,3000\n0,2500000,10,1101,2010,3020\n0,3500000,10,1201,2030,3040\n";

    #[test]
    fn tares_series_and_table() -> Result<(), NetError> {
        let frames = parse_series(SERIES)?;
        assert_eq!((frames.len(), runs(&frames)), (5, vec![0]));
        assert_eq!(tare_pa(&frames, 0)?, [1001.0, 2000.0, 3000.0]);
        let all = frame_samples(&frames, 0)?;
        assert_eq!(all[4].rise_hpa, [2.0, 0.3, 0.4]);
        // Step 0's settled second holds one frame (1.5 s), step 1's one (3.5 s).
        let steps = step_samples(&frames, 0)?;
        assert_eq!(steps.len(), 2);
        assert_eq!(
            (steps[1].rise_hpa, steps[1].weight_gf),
            ([2.0, 0.3, 0.4], 10.0)
        );
        assert!(matches!(tare_pa(&frames, 1), Err(NetError::Data { .. })));
        let t = tared_table(&[(0.0, [1.0, 2.0, 3.0]), (50.0, [1.5, 2.0, 3.25])])?;
        assert_eq!(t[1].rise_hpa, [0.5, 0.0, 0.25]);
        assert!(tared_table(&[(5.0, [1.0; 3])]).is_err());
        assert!(tared_table(&[(0.0, [1.0; 3]), (1.0, [f64::NAN; 3])]).is_err());
        assert!(matches!(
            parse_series("0,1,2\n"),
            Err(NetError::Data { line: 1, .. })
        ));
        Ok(())
    }
}
