//! Helpers shared by the imu_pad tests: run taps through the driver and summarise them.
#![allow(dead_code, unreachable_pub, missing_docs)]

use hand_sim::imu_pad::dataset::{DatasetSpec, TapRecord, generate};
use hand_sim::imu_pad::{ImuPadConfig, TapPosition};

/// Every tap of `positions` × `depths` × `repeats`, through the driver.
pub fn taps(positions: &[TapPosition], depths: &[f64], repeats: u32, seed: u64) -> Vec<TapRecord> {
    let spec = DatasetSpec {
        seed,
        depths_mm: depths.to_vec(),
        repeats,
        positions: positions.to_vec(),
        pad: ImuPadConfig::default(),
    };
    generate(&spec).expect("dataset generation")
}

/// Mean over repeats of `f(record)` for each position, at depth `depth`.
pub fn mean_by_position(
    records: &[TapRecord],
    depth: f64,
    f: impl Fn(&TapRecord) -> f64,
) -> Vec<(TapPosition, f64)> {
    let mut out: Vec<(TapPosition, f64, u32)> = Vec::new();
    for r in records.iter().filter(|r| (r.depth_mm - depth).abs() < 1e-9) {
        match out.iter_mut().find(|(p, _, _)| *p == r.position) {
            Some((_, sum, n)) => {
                *sum += f(r);
                *n += 1;
            }
            None => out.push((r.position, f(r), 1)),
        }
    }
    out.into_iter()
        .map(|(p, s, n)| (p, s / f64::from(n)))
        .collect()
}

/// Mean of window signal `s` over its 38 samples.
pub fn window_mean(r: &TapRecord, s: usize) -> f64 {
    r.window.signals[s]
        .iter()
        .map(|v| f64::from(*v))
        .sum::<f64>()
        / 38.0
}

/// Largest |value| of window signal `s`.
pub fn window_peak_abs(r: &TapRecord, s: usize) -> f64 {
    r.window.signals[s]
        .iter()
        .map(|v| f64::from(v.abs()))
        .fold(0.0, f64::max)
}
