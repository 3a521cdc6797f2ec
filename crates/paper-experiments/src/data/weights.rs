//! Weight datasets for the force DNN (seed 000 §2.2): three fingertip pressures → the weight
//! resting on the pad.
//!
//! Every sample is *tared*: its inputs are the pressure rises above the sensors' own unloaded
//! reading, in hPa (the paper's three sensors rest at 1191, 1199 and 1018 hPa, the simulated
//! ones near 1010 hPa with a different offset every power-up; the weight is in the rise).
//!
//! - Table 1 ([`tared_table`]): 13 rows as printed; the tare is the 0 gf row.
//! - The hand-sim series (`fixtures/datasets/fingertip/weights.csv`, schema [`WeightRow`],
//!   read by [`load_series`] into a [`WeightSeries`] of arrays): three runs of 0 → 200 gf in
//!   10 gf steps held 2 s each, read at OSR 4096 every ~18 ms with the sensors drifting
//!   0.1 hPa/min. Each run's tare is the mean of its first [`TARE_US`] µs (nothing on the pad
//!   yet), as a scale zeroes itself at power-up.

use hand_sim::fingertip::dataset::{WeightReading, WeightRow};
use hand_sim::records::{self, DatasetError};
use ndarray::{Array1, Array2};
use std::path::{Path, PathBuf};
use tactile_nets::error::NetError;

/// Length of the unloaded window at the start of a run that sets its tare, µs.
pub const TARE_US: i64 = 1_000_000;
/// How long a weight is held in the simulated series, µs.
pub const STEP_US: i64 = 2_000_000;
/// The settled part of a step that a step average reads: its last second, µs.
pub const SETTLED_US: i64 = 1_000_000;

pub use tactile_nets::force_dnn::{WeightSample, tared_table};

/// Weight-series frames (`weights.csv`, or a live run), one entry per frame in every array.
#[derive(Debug, Clone, PartialEq)]
pub struct WeightSeries {
    /// Each frame's run (0, 1, 2 in the file).
    pub run: Array1<u32>,
    /// Time since the run started, µs.
    pub t_us: Array1<i64>,
    /// The weight on the pad, gf.
    pub weight_gf: Array1<f32>,
    /// Frames × 3: sensors 1–3, Pa.
    pub pressure_pa: Array2<f32>,
}

impl WeightSeries {
    /// Run `run`'s readings from hand-sim's fingertip
    /// ([`weight_run`](hand_sim::fingertip::dataset::weight_run)), in time order.
    pub fn from_readings(run: u32, readings: &[WeightReading]) -> WeightSeries {
        WeightSeries {
            run: Array1::from_elem(readings.len(), run),
            t_us: readings.iter().map(|r| r.t_us as i64).collect(),
            weight_gf: readings.iter().map(|r| r.weight_gf as f32).collect(),
            pressure_pa: Array2::from(readings.iter().map(|r| r.pressure_pa).collect::<Vec<_>>()),
        }
    }

    /// Frames in the series.
    pub fn len(&self) -> usize {
        self.run.len()
    }

    /// Whether it has no frame.
    pub fn is_empty(&self) -> bool {
        self.run.is_empty()
    }

    /// The runs present, ascending.
    pub fn runs(&self) -> Vec<u32> {
        let mut v = self.run.to_vec();
        v.sort_unstable();
        v.dedup();
        v
    }

    /// The frames of `run`, in series order.
    fn frames_of(&self, run: u32) -> impl Iterator<Item = usize> + '_ {
        (0..self.len()).filter(move |&i| self.run[i] == run)
    }

    /// Mean pressure of `run`'s first [`TARE_US`] µs, Pa.
    ///
    /// Errors: [`NetError::Data`] when the run has no frame in that window or it is loaded.
    pub fn tare_pa(&self, run: u32) -> Result<[f64; 3], NetError> {
        let window: Vec<usize> = self
            .frames_of(run)
            .filter(|&i| self.t_us[i] < TARE_US)
            .collect();
        if window.is_empty() || window.iter().any(|&i| self.weight_gf[i] != 0.0) {
            return Err(NetError::Data {
                line: 0,
                reason: format!("run {run} has no unloaded frames in its first {TARE_US} µs"),
            });
        }
        let n = window.len() as f64;
        Ok(core::array::from_fn(|k| {
            window
                .iter()
                .map(|&i| f64::from(self.pressure_pa[[i, k]]))
                .sum::<f64>()
                / n
        }))
    }

    /// Every frame of `run` as a tared sample (rises in hPa), in time order.
    pub fn frame_samples(&self, run: u32) -> Result<Vec<WeightSample>, NetError> {
        let tare = self.tare_pa(run)?;
        Ok(self
            .frames_of(run)
            .map(|i| WeightSample {
                rise_hpa: core::array::from_fn(|k| {
                    ((f64::from(self.pressure_pa[[i, k]]) - tare[k]) / 100.0) as f32
                }),
                weight_gf: self.weight_gf[i],
            })
            .collect())
    }

    /// One sample per weight step of `run`: the mean tared rise over the step's settled last
    /// [`SETTLED_US`] µs (the paper's "average measured values" of Table 1).
    pub fn step_samples(&self, run: u32) -> Result<Vec<WeightSample>, NetError> {
        let tare = self.tare_pa(run)?;
        let mut steps: Vec<(i64, [f64; 3], usize, f32)> = Vec::new();
        for i in self.frames_of(run) {
            let t_us = self.t_us[i];
            let step = t_us.div_euclid(STEP_US);
            if t_us - step * STEP_US < STEP_US - SETTLED_US {
                continue;
            }
            if steps.last().is_none_or(|s| s.0 != step) {
                steps.push((step, [0.0; 3], 0, self.weight_gf[i]));
            }
            if let Some(s) = steps.last_mut() {
                for (k, (sum, t)) in s.1.iter_mut().zip(tare).enumerate() {
                    *sum += f64::from(self.pressure_pa[[i, k]]) - t;
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
}

/// `weights.csv` below the workspace root `root`.
pub fn series_path(root: &Path) -> PathBuf {
    root.join("fixtures/datasets/fingertip/weights.csv")
}

/// Reads the committed weight series below the workspace root `root`.
pub fn load_series(root: &Path) -> Result<WeightSeries, DatasetError> {
    let path = series_path(root);
    series(&path, records::read(&path)?)
}

/// Parses `weights.csv` text (named so in errors).
pub fn parse_series(text: &str) -> Result<WeightSeries, DatasetError> {
    let path = Path::new("weights.csv");
    series(path, records::parse(path, text)?)
}

/// The series of the rows of `file`; a run's frames run forward in time.
fn series(file: &Path, rows: Vec<records::Row<WeightRow>>) -> Result<WeightSeries, DatasetError> {
    let mut last: Vec<(u32, u64)> = Vec::new();
    for r in &rows {
        let (run, t_us) = (r.record.run, r.record.t_us);
        match last.iter_mut().find(|(k, _)| *k == run) {
            Some((_, t)) if *t >= t_us => {
                return Err(DatasetError::value(
                    file,
                    r.line,
                    "t_us",
                    format!("run {run} goes back in time to {t_us} µs"),
                ));
            }
            Some((_, t)) => *t = t_us,
            None => last.push((run, t_us)),
        }
    }
    let t_us = rows
        .iter()
        .map(|r| {
            i64::try_from(r.record.t_us)
                .map_err(|_| DatasetError::value(file, r.line, "t_us", "too large"))
        })
        .collect::<Result<_, _>>()?;
    Ok(WeightSeries {
        run: rows.iter().map(|r| r.record.run).collect(),
        t_us,
        weight_gf: rows.iter().map(|r| r.record.weight_gf.0 as f32).collect(),
        pressure_pa: Array2::from(
            rows.iter()
                .map(|r| [r.record.p1_pa.0, r.record.p2_pa.0, r.record.p3_pa.0])
                .collect::<Vec<_>>(),
        ),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use hand_sim::records::ErrorKind;

    const SERIES: &str = "# comment\nrun,t_us,weight_gf,p1_pa,p2_pa,p3_pa\n\
        0,100,0,1000,2000,3000\n0,900000,0,1002,2000,3000\n\
        0,1500000,0,1001,2000,3000\n0,2500000,10,1101,2010,3020\n0,3500000,10,1201,2030,3040\n";

    #[test]
    fn tares_series_and_table() -> Result<(), Box<dyn std::error::Error>> {
        let frames = parse_series(SERIES)?;
        assert_eq!((frames.len(), frames.runs()), (5, vec![0]));
        assert_eq!(frames.pressure_pa.dim(), (5, 3));
        assert_eq!(frames.tare_pa(0)?, [1001.0, 2000.0, 3000.0]);
        let all = frames.frame_samples(0)?;
        assert_eq!(all[4].rise_hpa, [2.0, 0.3, 0.4]);
        // Step 0's settled second holds one frame (1.5 s), step 1's one (3.5 s).
        let steps = frames.step_samples(0)?;
        assert_eq!(steps.len(), 2);
        assert_eq!(
            (steps[1].rise_hpa, steps[1].weight_gf),
            ([2.0, 0.3, 0.4], 10.0)
        );
        assert!(matches!(frames.tare_pa(1), Err(NetError::Data { .. })));
        let t = tared_table(&[(0.0, [1.0, 2.0, 3.0]), (50.0, [1.5, 2.0, 3.25])])?;
        assert_eq!(t[1].rise_hpa, [0.5, 0.0, 0.25]);
        assert!(tared_table(&[(5.0, [1.0; 3])]).is_err());
        assert!(tared_table(&[(0.0, [1.0; 3]), (1.0, [f64::NAN; 3])]).is_err());
        Ok(())
    }

    #[test]
    fn bad_files_are_errors_naming_line_and_column() {
        let error = |text: &str| parse_series(text).expect_err("a bad series");
        let e = error("0,1,2\n");
        assert!(matches!(e.kind, ErrorKind::WrongColumn { .. }), "{e}");
        let e = error(&SERIES.replace("\n0,2500000,10,", "\n0,2500000,ten,"));
        assert_eq!((e.line, e.column.as_deref()), (Some(6), Some("weight_gf")));
        let e = error(&SERIES.replace(",1201,", ",NaN,"));
        assert!(matches!(e.kind, ErrorKind::NotFinite { .. }));
        assert_eq!((e.line, e.column.as_deref()), (Some(7), Some("p1_pa")));
        let e = error(&SERIES.replace("0,3500000,", "0,2400000,"));
        assert_eq!((e.line, e.column.as_deref()), (Some(7), Some("t_us")));
    }

    #[test]
    fn a_live_run_is_a_series() -> Result<(), NetError> {
        let readings: Vec<WeightReading> = (0..4u64)
            .map(|i| WeightReading {
                t_us: i * 400_000,
                weight_gf: 0.0,
                pressure_pa: [1.0, 2.0, 3.0 + i as f32],
            })
            .collect();
        let s = WeightSeries::from_readings(2, &readings);
        assert_eq!(s.runs(), [2]);
        assert_eq!(s.pressure_pa[[3, 2]], 6.0);
        assert_eq!(s.tare_pa(2)?, [1.0, 2.0, 4.0]);
        Ok(())
    }
}
