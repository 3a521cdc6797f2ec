//! The simulated barometric fingertip's tap dataset (`fixtures/datasets/fingertip/`, written by
//! `hand-sim`): `taps.csv` (one row per tap: shape, cell mask, eq. 4 label, force, held
//! pressures) and `series.csv` (the raw driver readings from 30 ms before to 90 ms after onset).
//!
//! From the series this module takes each sensor's resting baseline (mean and spread of the
//! frames before onset) and its arrival time: the first moment the reading rises more than
//! [`ARRIVAL_SIGMAS`] spreads (at least [`ARRIVAL_MIN_PA`]) above the baseline, linearly
//! interpolated between the two frames around the crossing.

use std::path::{Path, PathBuf};
use tactile_nets::NetError;
pub use tactile_nets::contact_mlp::{ContactExample, TapReading};

/// Rise above baseline, in baseline standard deviations, that counts as arrival.
pub const ARRIVAL_SIGMAS: f32 = 5.0;
/// Smallest rise that counts as arrival, Pa (the driver reports whole pascals).
pub const ARRIVAL_MIN_PA: f32 = 4.0;

/// One tap of `taps.csv`.
#[derive(Debug, Clone, PartialEq)]
pub struct Tap {
    /// Tap id (row of `series.csv`).
    pub id: u32,
    /// MS5611 oversampling ratio the pad was read at.
    pub osr: u16,
    /// Figure 7 shape name (`1`, `4-1`, `9`, `16`, `12`, `4-2`).
    pub shape: String,
    /// Cells touched.
    pub size: u8,
    /// Cell set: bit `i` = cell `i` of the 4 × 6 pad, row-major, cell 0 = area 1.1.
    pub mask: u32,
    /// Eq. 4 average-area label.
    pub average_area: f32,
    /// 3 × 3 region (0–8) of the patch centroid.
    pub aot_region: u8,
    /// Contact force, kgf.
    pub force_kgf: f32,
    /// Repeat index (0 or 1).
    pub repeat: u32,
    /// Held pressure of sensors 1–3, Pa.
    pub held_pa: [f32; 3],
}

/// A tap with its reading.
#[derive(Debug, Clone, PartialEq)]
pub struct TapRecord {
    /// The row of `taps.csv`.
    pub tap: Tap,
    /// Baseline, held pressures and arrival times.
    pub reading: TapReading,
}

impl TapRecord {
    /// The MLP's training example: the reading and the touched cells.
    pub fn example(&self) -> ContactExample {
        ContactExample {
            reading: self.reading,
            mask: self.tap.mask,
        }
    }
}

/// One frame of `series.csv`: time from onset, µs, and the three pressures, Pa.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Frame {
    /// Time relative to contact onset, µs.
    pub t_us: i64,
    /// Sensors 1–3, Pa.
    pub pressure_pa: [f32; 3],
}

/// `taps.csv` and `series.csv` below the workspace root `root`.
pub fn dataset_paths(root: &Path) -> (PathBuf, PathBuf) {
    let dir = root.join("fixtures/datasets/fingertip");
    (dir.join("taps.csv"), dir.join("series.csv"))
}

/// Reads and joins the committed dataset below the workspace root `root`.
pub fn load(root: &Path) -> Result<Vec<TapRecord>, NetError> {
    let (taps, series) = dataset_paths(root);
    parse(
        &std::fs::read_to_string(taps)?,
        &std::fs::read_to_string(series)?,
    )
}

/// Parses `taps.csv` and `series.csv` text and joins them by tap id.
pub fn parse(taps_csv: &str, series_csv: &str) -> Result<Vec<TapRecord>, NetError> {
    let taps = parse_taps(taps_csv)?;
    let series = parse_series(series_csv)?;
    taps.into_iter()
        .map(|tap| {
            let frames = series
                .get(tap.id as usize)
                .filter(|f| !f.is_empty())
                .ok_or_else(|| NetError::Data {
                    line: 0,
                    reason: format!("tap {} has no series", tap.id),
                })?;
            let (baseline_pa, spread_pa) = baseline(frames).ok_or_else(|| NetError::Data {
                line: 0,
                reason: format!("tap {} has no frame before onset", tap.id),
            })?;
            let reading = TapReading {
                baseline_pa,
                held_pa: tap.held_pa,
                arrival_ms: arrival_ms(frames, baseline_pa, spread_pa),
            };
            Ok(TapRecord { tap, reading })
        })
        .collect()
}

/// Data lines of a CSV text with their 1-based line numbers (comments and header skipped).
pub(crate) fn data_lines<'a>(
    text: &'a str,
    header: &'a str,
) -> impl Iterator<Item = (usize, &'a str)> {
    text.lines()
        .enumerate()
        .map(|(i, l)| (i + 1, l.trim()))
        .filter(move |(_, l)| !l.is_empty() && !l.starts_with('#') && !l.starts_with(header))
}

/// Field `i` of a split line parsed as `T`, or a [`NetError::Data`] naming it.
pub(crate) fn field<T: std::str::FromStr>(
    fields: &[&str],
    i: usize,
    name: &str,
    line: usize,
) -> Result<T, NetError> {
    fields
        .get(i)
        .and_then(|s| s.parse().ok())
        .ok_or_else(|| NetError::Data {
            line,
            reason: format!("bad or missing `{name}`"),
        })
}

/// Parses `taps.csv`.
pub fn parse_taps(text: &str) -> Result<Vec<Tap>, NetError> {
    data_lines(text, "tap,")
        .map(|(line, l)| {
            let f: Vec<&str> = l.split(',').collect();
            if f.len() != 12 {
                return Err(NetError::Data {
                    line,
                    reason: format!("{} fields, expected 12", f.len()),
                });
            }
            Ok(Tap {
                id: field(&f, 0, "tap", line)?,
                osr: field(&f, 1, "osr", line)?,
                shape: f[2].to_owned(),
                size: field(&f, 3, "size", line)?,
                mask: field(&f, 4, "mask", line)?,
                average_area: field(&f, 5, "average_area", line)?,
                aot_region: field(&f, 6, "aot_region", line)?,
                force_kgf: field(&f, 7, "force_kgf", line)?,
                repeat: field(&f, 8, "repeat", line)?,
                held_pa: [
                    field(&f, 9, "held1_pa", line)?,
                    field(&f, 10, "held2_pa", line)?,
                    field(&f, 11, "held3_pa", line)?,
                ],
            })
        })
        .collect()
}

/// Parses `series.csv` into frames per tap id (index = id).
pub fn parse_series(text: &str) -> Result<Vec<Vec<Frame>>, NetError> {
    let mut out: Vec<Vec<Frame>> = Vec::new();
    for (line, l) in data_lines(text, "tap,") {
        let f: Vec<&str> = l.split(',').collect();
        if f.len() != 5 {
            return Err(NetError::Data {
                line,
                reason: format!("{} fields, expected 5", f.len()),
            });
        }
        let id: usize = field(&f, 0, "tap", line)?;
        if id >= out.len() {
            out.resize(id + 1, Vec::new());
        }
        out[id].push(Frame {
            t_us: field(&f, 1, "t_us", line)?,
            pressure_pa: [
                field(&f, 2, "p1_pa", line)?,
                field(&f, 3, "p2_pa", line)?,
                field(&f, 4, "p3_pa", line)?,
            ],
        });
    }
    Ok(out)
}

/// Mean and standard deviation of each sensor over the frames before onset (`t_us < 0`);
/// `None` when there is no such frame.
pub fn baseline(frames: &[Frame]) -> Option<([f32; 3], [f32; 3])> {
    let before: Vec<&Frame> = frames.iter().filter(|f| f.t_us < 0).collect();
    if before.is_empty() {
        return None;
    }
    let n = before.len() as f64;
    let mut mean = [0.0f32; 3];
    let mut spread = [0.0f32; 3];
    for k in 0..3 {
        let m = before
            .iter()
            .map(|f| f64::from(f.pressure_pa[k]))
            .sum::<f64>()
            / n;
        let var = before
            .iter()
            .map(|f| (f64::from(f.pressure_pa[k]) - m).powi(2))
            .sum::<f64>()
            / n;
        mean[k] = m as f32;
        spread[k] = var.sqrt() as f32;
    }
    Some((mean, spread))
}

/// Each sensor's arrival time after onset, ms (see the module docs); `None` if it never rose.
pub fn arrival_ms(
    frames: &[Frame],
    baseline_pa: [f32; 3],
    spread_pa: [f32; 3],
) -> [Option<f32>; 3] {
    let mut out = [None; 3];
    for (k, slot) in out.iter_mut().enumerate() {
        let threshold = (ARRIVAL_SIGMAS * spread_pa[k]).max(ARRIVAL_MIN_PA);
        let rise = |f: &Frame| f.pressure_pa[k] - baseline_pa[k];
        let mut prev: Option<&Frame> = None;
        for f in frames.iter().filter(|f| f.t_us >= 0) {
            if rise(f) > threshold {
                let t = match prev {
                    Some(p) if rise(f) > rise(p) => {
                        let frac = ((threshold - rise(p)) / (rise(f) - rise(p))).clamp(0.0, 1.0);
                        p.t_us as f32 + frac * (f.t_us - p.t_us) as f32
                    }
                    _ => f.t_us as f32,
                };
                *slot = Some(t / 1000.0);
                break;
            }
            prev = Some(f);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    const TAPS: &str = "# comment\n\
        tap,osr,shape,size,mask,average_area,aot_region,force_kgf,repeat,held1_pa,held2_pa,held3_pa\n\
        0,256,1,1,1,1.1000,0,5,0,102345.8,101041.8,103412.7\n";
    const SERIES: &str = "tap,t_us,p1_pa,p2_pa,p3_pa\n\
        0,-2000,100,200,300\n0,-1000,102,200,300\n0,0,101,200,300\n\
        0,1000,111,200,300\n0,2000,131,200,400\n";

    #[test]
    fn parses_and_finds_arrivals() -> Result<(), NetError> {
        let r = parse(TAPS, SERIES)?;
        assert_eq!(r.len(), 1);
        assert_eq!(r[0].tap.mask, 1);
        assert_eq!(r[0].tap.held_pa[2], 103412.7);
        assert_eq!(r[0].reading.baseline_pa, [101.0, 200.0, 300.0]);
        // Sensor 1: spread 1 Pa -> threshold 5 Pa, crossed between 0 (0 Pa) and 1 ms (10 Pa);
        // sensor 3: no spread -> 4 Pa, crossed between 1 ms (0 Pa) and 2 ms (100 Pa).
        let [a, b, c] = r[0].reading.arrival_ms;
        assert_eq!((a, b), (Some(0.5), None));
        assert!((c.unwrap_or(f32::NAN) - 1.04).abs() < 1e-5);
        Ok(())
    }

    #[test]
    fn bad_lines_are_typed_errors() {
        assert!(matches!(
            parse_taps("0,256,1\n"),
            Err(NetError::Data { line: 1, .. })
        ));
        assert!(matches!(
            parse_series("x,1,2,3,4\n"),
            Err(NetError::Data { line: 1, .. })
        ));
        assert!(matches!(
            parse(TAPS, "tap,t_us\n"),
            Err(NetError::Data { .. })
        ));
    }
}
