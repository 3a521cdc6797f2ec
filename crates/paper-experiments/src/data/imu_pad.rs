//! The simulated ICM-20789 pad's tap dataset (`fixtures/datasets/imu_pad/taps.csv`, written by
//! `hand-sim`, seed 002 §III-C / §IV-A; schema [`ImuTapRow`]): one row per tap with its grid
//! position, §IV-A region, depth, pressure peak and the 4 × 38 window (acc x, acc y, gyro x,
//! gyro y), read into a [`Dataset`]: the taps' labels and an N × 4 × 38 array of windows.

use hand_sim::imu_pad::dataset::ImuTapRow;
use hand_sim::records::{self, DatasetError, Row};
use ndarray::{Array3, ArrayView2, Axis};
use std::path::{Path, PathBuf};

pub use tactile_nets::contact_cnn::{CHANNELS, REGIONS, WINDOW, WINDOW_VALUES};

/// Deepest contact a row may state, mm.
const MAX_DEPTH_MM: f64 = 10.0;

/// One tap of `taps.csv`: its labels (its window is in [`Dataset::windows`]).
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
}

impl ImuTap {
    /// The grid position as one index 0…71 (row-major over 24 rows × 3 columns).
    pub fn position(&self) -> usize {
        (usize::from(self.row) - 1) * 3 + usize::from(self.column) - 1
    }
}

/// The tap dataset: labels and windows.
#[derive(Debug, Clone, PartialEq)]
pub struct Dataset {
    /// The taps in file order.
    pub taps: Vec<ImuTap>,
    /// Taps × [`CHANNELS`] × [`WINDOW`]: acc x, acc y (mm/s²), gyro x, gyro y (mrad/s);
    /// `windows[[i, c, s]]` is channel `c` at sample `s` of `taps[i]`.
    pub windows: Array3<f32>,
}

impl Dataset {
    /// Taps in the dataset.
    pub fn len(&self) -> usize {
        self.taps.len()
    }

    /// Whether it has no tap.
    pub fn is_empty(&self) -> bool {
        self.taps.is_empty()
    }

    /// The window of tap `i` (4 × 38), `None` past the last tap.
    pub fn window(&self, i: usize) -> Option<ArrayView2<'_, f32>> {
        (i < self.windows.len_of(Axis(0))).then(|| self.windows.index_axis(Axis(0), i))
    }

    /// The window of tap `i` flattened channel-major, as the CNN reads it; `None` past the
    /// last tap.
    pub fn window_values(&self, i: usize) -> Option<[f32; WINDOW_VALUES]> {
        let w = self.window(i)?;
        let mut out = [0.0f32; WINDOW_VALUES];
        for (o, v) in out.iter_mut().zip(w.iter()) {
            *o = *v;
        }
        Some(out)
    }

    /// The distinct depths, µm, ascending.
    pub fn depths_um(&self) -> Vec<u32> {
        let mut v: Vec<u32> = self.taps.iter().map(|t| t.depth_um).collect();
        v.sort_unstable();
        v.dedup();
        v
    }
}

/// `taps.csv` below the workspace root `root`.
pub fn dataset_path(root: &Path) -> PathBuf {
    root.join("fixtures/datasets/imu_pad/taps.csv")
}

/// Reads the committed dataset below the workspace root `root`.
pub fn load(root: &Path) -> Result<Dataset, DatasetError> {
    let path = dataset_path(root);
    dataset(&path, records::read(&path)?)
}

/// Parses `taps.csv` text (named so in errors).
pub fn parse(text: &str) -> Result<Dataset, DatasetError> {
    let path = Path::new("taps.csv");
    dataset(path, records::parse(path, text)?)
}

/// The dataset of the rows of `file`, each checked against the grid.
fn dataset(file: &Path, rows: Vec<Row<ImuTapRow>>) -> Result<Dataset, DatasetError> {
    let mut taps = Vec::with_capacity(rows.len());
    let mut windows = Vec::with_capacity(rows.len() * WINDOW_VALUES);
    for Row { line, record: r } in rows {
        let within = |column: &str, v: u8, lo: u8, hi: u8| {
            if (lo..=hi).contains(&v) {
                Ok(v)
            } else {
                Err(DatasetError::value(
                    file,
                    line,
                    column,
                    format!("{v} is outside {lo}…{hi}"),
                ))
            }
        };
        let depth_mm = r.depth_mm.0;
        if !(0.0..=MAX_DEPTH_MM).contains(&depth_mm) {
            return Err(DatasetError::value(
                file,
                line,
                "depth_mm",
                format!("{depth_mm} mm is outside 0…{MAX_DEPTH_MM} mm"),
            ));
        }
        taps.push(ImuTap {
            depth_um: (depth_mm * 1000.0).round() as u32,
            repeat: r.repeat,
            column: within("column", r.column, 1, 3)?,
            row: within("row", r.row, 1, 24)?,
            region: within("region", r.region, 0, REGIONS as u8 - 1)?,
            force_n: r.force_n.0 as f32,
            pressure_peak_counts: r.pressure_peak_counts.0 as f32,
        });
        windows.extend(r.window.signals().iter().flatten().map(|&v| v as f32));
    }
    let windows = Array3::from_shape_vec((taps.len(), CHANNELS, WINDOW), windows)
        .map_err(|e| DatasetError::rule(file, None, e.to_string()))?;
    Ok(Dataset { taps, windows })
}

#[cfg(test)]
mod tests {
    use super::*;
    use hand_sim::imu_pad::dataset::csv_header;
    use hand_sim::records::ErrorKind;

    fn row(region: &str, value: &str) -> String {
        let w = vec![value; WINDOW_VALUES].join(",");
        format!("0.4,2,3,9,{region},1.5,0.0,{w}\n")
    }

    fn file(rows: &str) -> String {
        format!("# c\n{}\n{rows}", csv_header())
    }

    #[test]
    fn parses_a_row_and_rejects_bad_ones() -> Result<(), DatasetError> {
        let data = parse(&file(&row("5", "-15")))?;
        assert_eq!(data.len(), 1);
        let t = &data.taps[0];
        assert_eq!(
            (t.depth_um, t.repeat, t.column, t.row, t.region),
            (400, 2, 3, 9, 5)
        );
        assert_eq!(t.position(), 26);
        assert_eq!(data.windows.dim(), (1, CHANNELS, WINDOW));
        assert!(data.windows.iter().all(|&v| v == -15.0));
        assert_eq!(
            data.window_values(0).map(|w| w[WINDOW_VALUES - 1]),
            Some(-15.0)
        );
        assert_eq!(data.window_values(1), None);
        // A region out of range, NaN, a gyro value in an accelerometer column, a short row.
        let e = parse(&file(&row("9", "0"))).expect_err("region 9");
        assert_eq!((e.line, e.column.as_deref()), (Some(3), Some("region")));
        let e = parse(&file(&row("1", "NaN"))).expect_err("NaN");
        assert!(matches!(e.kind, ErrorKind::NotFinite { .. }));
        assert_eq!((e.line, e.column.as_deref()), (Some(3), Some("ax_00")));
        let e = parse(&file(&row("1", "-1.5"))).expect_err("a fraction of mm/s²");
        assert_eq!((e.line, e.column.as_deref()), (Some(3), Some("ax_00")));
        let e = parse(&file("0.2,0,1\n")).expect_err("a short row");
        assert!(matches!(e.kind, ErrorKind::FieldCount { found: 3, .. }));
        let e = parse("depth_mm,repeat\n").expect_err("a short header");
        assert!(matches!(e.kind, ErrorKind::MissingColumn));
        assert_eq!(e.column.as_deref(), Some("column"));
        Ok(())
    }
}
