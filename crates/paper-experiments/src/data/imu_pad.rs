//! The simulated ICM-20789 pad's tap dataset (`fixtures/datasets/imu_pad/taps.csv`, written by
//! `hand-sim`, seed 002 §III-C / §IV-A): one row per tap with its grid position, §IV-A region,
//! depth, pressure peak and the 4 × 38 window (acc x, acc y, gyro x, gyro y).

use std::path::{Path, PathBuf};
use tactile_nets::error::NetError;

pub use tactile_nets::contact_cnn::{CHANNELS, REGIONS, WINDOW, WINDOW_VALUES};

/// One tap of `taps.csv`.
#[derive(Debug, Clone, PartialEq)]
pub struct ImuTap {
    /// Nominal contact depth, µm (0.2 mm = 200), an integer so depths compare exactly.
    pub depth_um: u32,
    /// Repeat 0…4.
    pub repeat: u32,
    /// Grid column 1…3.
    pub column: u8,
    /// Grid row 1…24.
    pub row: u8,
    /// §IV-A region 0…8.
    pub region: u8,
    /// True peak tap force, N (not a chip reading).
    pub force_n: f32,
    /// Driver-read pressure peak over the rest mean, counts (1 count = 1 Pa).
    pub pressure_peak_counts: f32,
    /// The window, channel-major: acc x, acc y (mm/s²), gyro x, gyro y (mrad/s).
    pub window: [f32; WINDOW_VALUES],
}

impl ImuTap {
    /// The grid position as one index 0…71 (row-major over 24 rows × 3 columns).
    pub fn position(&self) -> usize {
        (usize::from(self.row) - 1) * 3 + usize::from(self.column) - 1
    }
}

/// `taps.csv` below the workspace root `root`.
pub fn dataset_path(root: &Path) -> PathBuf {
    root.join("fixtures/datasets/imu_pad/taps.csv")
}

/// Reads the committed dataset below the workspace root `root`.
pub fn load(root: &Path) -> Result<Vec<ImuTap>, NetError> {
    parse(&std::fs::read_to_string(dataset_path(root))?)
}

/// Parses `taps.csv` text (comments `#` and the header skipped).
pub fn parse(text: &str) -> Result<Vec<ImuTap>, NetError> {
    const FIXED: usize = 7;
    let mut out = Vec::new();
    for (i, l) in text.lines().enumerate() {
        let (line, l) = (i + 1, l.trim());
        if l.is_empty() || l.starts_with('#') || l.starts_with("depth_mm,") {
            continue;
        }
        let f: Vec<&str> = l.split(',').collect();
        if f.len() != FIXED + WINDOW_VALUES {
            return Err(NetError::Data {
                line,
                reason: format!("{} fields, expected {}", f.len(), FIXED + WINDOW_VALUES),
            });
        }
        let num = |k: usize, name: &str| -> Result<f64, NetError> {
            f[k].parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| NetError::Data {
                    line,
                    reason: format!("bad `{name}`: {:?}", f[k]),
                })
        };
        let int = |k: usize, name: &str, lo: u32, hi: u32| -> Result<u32, NetError> {
            f[k].parse::<u32>()
                .ok()
                .filter(|v| (lo..=hi).contains(v))
                .ok_or_else(|| NetError::Data {
                    line,
                    reason: format!("bad `{name}` (expected {lo}…{hi}): {:?}", f[k]),
                })
        };
        let depth_mm = num(0, "depth_mm")?;
        if !(0.0..=10.0).contains(&depth_mm) {
            return Err(NetError::Data {
                line,
                reason: format!("depth {depth_mm} mm out of range"),
            });
        }
        let mut window = [0.0f32; WINDOW_VALUES];
        for (j, w) in window.iter_mut().enumerate() {
            *w = num(FIXED + j, "window value")? as f32;
        }
        out.push(ImuTap {
            depth_um: (depth_mm * 1000.0).round() as u32,
            repeat: int(1, "repeat", 0, u32::MAX)?,
            column: int(2, "column", 1, 3)? as u8,
            row: int(3, "row", 1, 24)? as u8,
            region: int(4, "region", 0, REGIONS as u32 - 1)? as u8,
            force_n: num(5, "force_n")? as f32,
            pressure_peak_counts: num(6, "pressure_peak_counts")? as f32,
            window,
        });
    }
    Ok(out)
}

/// The distinct depths in `taps`, µm, ascending.
pub fn depths_um(taps: &[ImuTap]) -> Vec<u32> {
    let mut v: Vec<u32> = taps.iter().map(|t| t.depth_um).collect();
    v.sort_unstable();
    v.dedup();
    v
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(region: &str, value: &str) -> String {
        let w = vec![value; WINDOW_VALUES].join(",");
        format!("0.4,2,3,9,{region},1.5,0.0,{w}\n")
    }

    #[test]
    fn parses_a_row_and_rejects_bad_ones() -> Result<(), NetError> {
        let text = format!("# c\ndepth_mm,repeat\n{}", row("5", "-1.5"));
        let taps = parse(&text)?;
        assert_eq!(taps.len(), 1);
        let t = &taps[0];
        assert_eq!(
            (t.depth_um, t.repeat, t.column, t.row, t.region),
            (400, 2, 3, 9, 5)
        );
        assert_eq!(t.position(), 26);
        assert!(t.window.iter().all(|&v| v == -1.5));
        assert!(matches!(
            parse(&row("9", "0")),
            Err(NetError::Data { line: 1, .. })
        ));
        assert!(matches!(
            parse(&row("1", "NaN")),
            Err(NetError::Data { line: 1, .. })
        ));
        assert!(matches!(
            parse("0.2,0,1\n"),
            Err(NetError::Data { line: 1, .. })
        ));
        Ok(())
    }
}
