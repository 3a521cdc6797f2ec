//! The simulated barometric fingertip's tap dataset (`fixtures/datasets/fingertip/`, written by
//! `hand-sim`): `taps.csv` (one row per tap: shape, cell mask, eq. 4 label, force, held
//! pressures; schema [`TapRow`]) and `series.csv` (the raw driver readings from 30 ms before to
//! 90 ms after onset; schema [`SeriesRow`]), read into one [`Dataset`]: the taps and each
//! tap's series as arrays.
//!
//! From the series this module takes each sensor's resting baseline (mean and spread of the
//! frames before onset) and its arrival time: the first moment the reading rises more than
//! [`ARRIVAL_SIGMAS`] spreads (at least [`ARRIVAL_MIN_PA`]) above the baseline, linearly
//! interpolated between the two frames around the crossing.

use hand_sim::fingertip::dataset::{SeriesRow, TapRow};
use hand_sim::records::{self, DatasetError, Row};
use ndarray::{Array1, Array2, ArrayView1, Axis};
use std::path::{Path, PathBuf};
pub use tactile_nets::contact_mlp::{ContactExample, TapReading};

/// Rise above baseline, in baseline standard deviations, that counts as arrival.
pub const ARRIVAL_SIGMAS: f32 = 5.0;
/// Smallest rise that counts as arrival, Pa (the driver reports whole pascals).
pub const ARRIVAL_MIN_PA: f32 = 4.0;
/// The dataset's directory below the workspace root.
pub const DATASET_DIR: &str = "fixtures/datasets/fingertip";

/// One tap of `taps.csv`.
#[derive(Debug, Clone, PartialEq)]
pub struct Tap {
    /// Tap id: its index in the dataset, and its rows' `tap` in `series.csv`.
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
    /// 3 × 3 region (0–8, row-major) of the patch centroid: the Arrival-of-Time label.
    pub aot_region: u8,
    /// Contact force, kgf.
    pub force_kgf: u32,
    /// Repeat index (0 or 1; the draw, 0…2, in the jittered set).
    pub repeat: u32,
    /// Shift of the contact off its cells (x right, y up), mm: zero on the lattice.
    pub offset_mm: [f32; 2],
    /// Held pressure of sensors 1–3, Pa.
    pub held_pa: [f32; 3],
}

impl Tap {
    /// The patch centroid in pad millimetres (x right, y up, origin at the pad centre; 3 mm
    /// cells): the cells' centroid plus the shift. `None` for an empty mask.
    pub fn centroid_mm(&self) -> Option<[f32; 2]> {
        let centroid = aot_locate::CellSet::from_bits(self.mask)?.centroid()?;
        let [x, y] = hand_sim::fingertip::geometry::PAD.grid_point_mm(centroid);
        Some([x + self.offset_mm[0], y + self.offset_mm[1]])
    }

    /// The patch centroid in 1-based (row, column) cell units, cell centres at whole numbers:
    /// [`Tap::centroid_mm`] on the 4 × 6 grid (the contact MLP's centroid target). `None` for
    /// an empty mask.
    pub fn centroid(&self) -> Option<[f32; 2]> {
        Some(hand_sim::fingertip::geometry::PAD.grid_point_of(self.centroid_mm()?))
    }
}

/// A tap's frames from 30 ms before to 90 ms after contact onset, in time order.
#[derive(Debug, Clone, PartialEq)]
pub struct TapSeries {
    /// Each frame's time relative to onset, µs (strictly increasing).
    pub t_us: Array1<i64>,
    /// Frames × 3: sensors 1–3 as the MS5611 driver decoded them, Pa.
    pub pressure_pa: Array2<f32>,
}

impl TapSeries {
    /// Each frame as (time from onset µs, the three pressures Pa), in time order.
    pub fn frames(&self) -> impl Iterator<Item = (i64, ArrayView1<'_, f32>)> {
        self.t_us
            .iter()
            .copied()
            .zip(self.pressure_pa.axis_iter(Axis(0)))
    }
}

/// The tap dataset: every tap with its series, which has a frame before onset.
#[derive(Debug, Clone, PartialEq)]
pub struct Dataset {
    taps: Vec<Tap>,
    series: Vec<TapSeries>,
}

impl Dataset {
    /// The taps, by id as read (`taps()[i].id == i`; [`Dataset::retain`] keeps the ids).
    pub fn taps(&self) -> &[Tap] {
        &self.taps
    }

    /// The series, one per tap: `series()[i]` is the series of `taps()[i]`.
    pub fn series(&self) -> &[TapSeries] {
        &self.series
    }

    /// Each tap with its series.
    pub fn iter(&self) -> impl Iterator<Item = (&Tap, &TapSeries)> {
        self.taps.iter().zip(&self.series)
    }

    /// Keeps the taps `keep` accepts (with their series).
    pub fn retain(&mut self, keep: impl Fn(&Tap) -> bool) {
        let (taps, series) = std::mem::take(&mut self.taps)
            .into_iter()
            .zip(std::mem::take(&mut self.series))
            .filter(|(t, _)| keep(t))
            .unzip();
        self.taps = taps;
        self.series = series;
    }

    /// Every tap with its reading: the baseline before onset, the held pressures and the
    /// arrival times (the contact MLP's input).
    pub fn records(&self) -> Vec<TapRecord> {
        // Every series of a dataset has a frame before onset, so every tap has a baseline.
        self.iter()
            .filter_map(|(tap, s)| {
                let (baseline_pa, spread_pa) = baseline(s)?;
                Some(TapRecord {
                    tap: tap.clone(),
                    reading: TapReading {
                        baseline_pa,
                        held_pa: tap.held_pa,
                        arrival_ms: arrival_ms(s, baseline_pa, spread_pa),
                    },
                })
            })
            .collect()
    }
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
    /// The MLP's training example: the reading, the touched cells and the (possibly shifted)
    /// centroid.
    pub fn example(&self) -> ContactExample {
        ContactExample {
            centroid: self.tap.centroid().unwrap_or([0.0, 0.0]),
            ..ContactExample::new(self.reading, self.tap.mask)
        }
    }
}

/// The four tap sets of the dataset.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TapSet {
    /// `taps.csv` / `series.csv`: every contact centred on its cells, two repeats (repeat 0
    /// trains, repeat 1 is held out).
    Lattice,
    /// `jittered_taps.csv` / `jittered_series.csv.gz` (gzipped: 3.8 MB of text): the same
    /// contacts shifted off the lattice within ± half a cell, three draws each; held out
    /// entirely.
    Jittered,
    /// `single_cell_taps.csv` / `single_cell_series.csv.gz`: one-cell contacts only, shifted
    /// the same way, 14 draws of each cell and force (1008 taps per OSR); held out entirely,
    /// for the 24-area figure.
    SingleCell,
    /// `single_cell_osr256_taps.csv` / `single_cell_osr256_series.csv.gz`: one-cell contacts
    /// shifted the same way, at the scene's OSR 256 only, 42 draws of each cell and force
    /// (3024 taps); held out entirely, to judge a model chosen after the other sets had been
    /// read.
    SingleCellOsr256,
}

impl TapSet {
    /// Its (taps, series) file names.
    pub fn files(self) -> (&'static str, &'static str) {
        match self {
            TapSet::Lattice => ("taps.csv", "series.csv"),
            TapSet::Jittered => ("jittered_taps.csv", "jittered_series.csv.gz"),
            TapSet::SingleCell => ("single_cell_taps.csv", "single_cell_series.csv.gz"),
            TapSet::SingleCellOsr256 => (
                "single_cell_osr256_taps.csv",
                "single_cell_osr256_series.csv.gz",
            ),
        }
    }
}

/// `taps.csv` and `series.csv` below the workspace root `root`.
pub fn dataset_paths(root: &Path) -> (PathBuf, PathBuf) {
    set_paths(root, TapSet::Lattice)
}

/// The (taps, series) files of `set` below the workspace root `root`.
pub fn set_paths(root: &Path, set: TapSet) -> (PathBuf, PathBuf) {
    let dir = root.join(DATASET_DIR);
    let (taps, series) = set.files();
    (dir.join(taps), dir.join(series))
}

/// Reads the committed lattice taps below the workspace root `root`.
pub fn load(root: &Path) -> Result<Dataset, DatasetError> {
    load_set(root, TapSet::Lattice)
}

/// Reads the committed tap set `set` below the workspace root `root`.
pub fn load_set(root: &Path, set: TapSet) -> Result<Dataset, DatasetError> {
    let (taps, series) = set_paths(root, set);
    join(
        &taps,
        records::read(&taps)?,
        &series,
        records::read(&series)?,
    )
}

/// Parses `taps.csv` and `series.csv` text (named so in errors) and joins them by tap id.
pub fn parse(taps_csv: &str, series_csv: &str) -> Result<Dataset, DatasetError> {
    let (taps, series) = (Path::new("taps.csv"), Path::new("series.csv"));
    join(
        taps,
        records::parse(taps, taps_csv)?,
        series,
        records::parse(series, series_csv)?,
    )
}

/// The dataset of the rows of both files. Taps are numbered 0, 1, 2… in file order; every
/// series row names one of them, a tap's frames run forward in time and every tap has a
/// frame before onset (its baseline).
fn join(
    taps_file: &Path,
    tap_rows: Vec<Row<TapRow>>,
    series_file: &Path,
    series_rows: Vec<Row<SeriesRow>>,
) -> Result<Dataset, DatasetError> {
    let mut taps = Vec::with_capacity(tap_rows.len());
    for Row { line, record: r } in tap_rows {
        if r.tap as usize != taps.len() {
            return Err(DatasetError::value(
                taps_file,
                line,
                "tap",
                format!("tap {} where tap {} belongs", r.tap, taps.len()),
            ));
        }
        taps.push(Tap {
            id: r.tap,
            osr: r.osr,
            shape: r.shape,
            size: r.size,
            mask: r.mask,
            average_area: r.average_area.0,
            aot_region: r.aot_region,
            force_kgf: r.force_kgf,
            repeat: r.repeat,
            offset_mm: [r.dx_mm.0 as f32, r.dy_mm.0 as f32],
            held_pa: [r.held1_pa.0, r.held2_pa.0, r.held3_pa.0].map(|p| p as f32),
        });
    }
    let mut frames: Vec<(Vec<i64>, Vec<f32>)> = vec![(Vec::new(), Vec::new()); taps.len()];
    for Row { line, record: r } in series_rows {
        let (t_us, p) = frames.get_mut(r.tap as usize).ok_or_else(|| {
            DatasetError::value(series_file, line, "tap", format!("no tap {}", r.tap))
        })?;
        if t_us.last().is_some_and(|&t| t >= r.t_us) {
            return Err(DatasetError::value(
                series_file,
                line,
                "t_us",
                format!("tap {} goes back in time to {} µs", r.tap, r.t_us),
            ));
        }
        t_us.push(r.t_us);
        p.extend([r.p1_pa.0, r.p2_pa.0, r.p3_pa.0]);
    }
    let series = frames
        .into_iter()
        .enumerate()
        .map(|(id, (t_us, p))| {
            if t_us.first().is_none_or(|&t| t >= 0) {
                return Err(DatasetError::rule(
                    series_file,
                    None,
                    format!("tap {id} has no frame before onset"),
                ));
            }
            let pressure_pa = Array2::from_shape_vec((t_us.len(), 3), p)
                .map_err(|e| DatasetError::rule(series_file, None, e.to_string()))?;
            Ok(TapSeries {
                t_us: Array1::from(t_us),
                pressure_pa,
            })
        })
        .collect::<Result<_, _>>()?;
    Ok(Dataset { taps, series })
}

/// Mean and standard deviation of each sensor over the frames before onset (`t_us < 0`);
/// `None` when there is no such frame.
pub fn baseline(series: &TapSeries) -> Option<([f32; 3], [f32; 3])> {
    let before: Vec<usize> = (0..series.t_us.len())
        .filter(|&i| series.t_us[i] < 0)
        .collect();
    if before.is_empty() {
        return None;
    }
    let mut mean = [0.0f32; 3];
    let mut spread = [0.0f32; 3];
    let rows = series.pressure_pa.select(Axis(0), &before);
    let n = before.len() as f64;
    for (k, column) in rows.axis_iter(Axis(1)).enumerate() {
        let m = column.iter().map(|&p| f64::from(p)).sum::<f64>() / n;
        let var = column
            .iter()
            .map(|&p| (f64::from(p) - m).powi(2))
            .sum::<f64>()
            / n;
        mean[k] = m as f32;
        spread[k] = var.sqrt() as f32;
    }
    Some((mean, spread))
}

/// Each sensor's arrival time after onset, ms (see the module docs); `None` if it never rose.
pub fn arrival_ms(
    series: &TapSeries,
    baseline_pa: [f32; 3],
    spread_pa: [f32; 3],
) -> [Option<f32>; 3] {
    let mut out = [None; 3];
    for (k, slot) in out.iter_mut().enumerate() {
        let threshold = (ARRIVAL_SIGMAS * spread_pa[k]).max(ARRIVAL_MIN_PA);
        let rise = |p: &ArrayView1<'_, f32>| p[k] - baseline_pa[k];
        let mut prev: Option<(i64, ArrayView1<'_, f32>)> = None;
        for (t_us, p) in series.frames().filter(|(t, _)| *t >= 0) {
            if rise(&p) > threshold {
                let t = match &prev {
                    Some((pt, pp)) if rise(&p) > rise(pp) => {
                        let frac = ((threshold - rise(pp)) / (rise(&p) - rise(pp))).clamp(0.0, 1.0);
                        *pt as f32 + frac * (t_us - pt) as f32
                    }
                    _ => t_us as f32,
                };
                *slot = Some(t / 1000.0);
                break;
            }
            prev = Some((t_us, p));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use hand_sim::records::ErrorKind;

    const TAPS: &str = "# comment\n\
        tap,osr,shape,size,mask,average_area,aot_region,force_kgf,repeat,dx_mm,dy_mm,held1_pa,held2_pa,held3_pa\n\
        0,256,1,1,1,1.1000,0,5,0,0.000,0.000,102345.8,101041.8,103412.7\n";
    const SERIES: &str = "tap,t_us,p1_pa,p2_pa,p3_pa\n\
        0,-2000,100,200,300\n0,-1000,102,200,300\n0,0,101,200,300\n\
        0,1000,111,200,300\n0,2000,131,200,400\n";

    #[test]
    fn parses_and_finds_arrivals() -> Result<(), DatasetError> {
        let data = parse(TAPS, SERIES)?;
        assert_eq!(data.series()[0].pressure_pa.dim(), (5, 3));
        let r = data.records();
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

    fn error(taps: &str, series: &str) -> DatasetError {
        match parse(taps, series) {
            Err(e) => e,
            Ok(d) => panic!("parsed {} taps of a bad dataset", d.taps().len()),
        }
    }

    #[test]
    fn bad_files_are_errors_naming_file_line_and_column() {
        // A bad row, a missing column, NaN: the file, the line and the column.
        let e = error(&TAPS.replace(",1,1,1.1000,", ",1,x,1.1000,"), SERIES);
        assert_eq!(
            (e.file.as_path(), e.line, e.column.as_deref()),
            (Path::new("taps.csv"), Some(3), Some("mask"))
        );
        let e = error(TAPS, "tap,t_us,p1_pa,p2_pa\n0,-1,1,2\n");
        assert!(matches!(e.kind, ErrorKind::MissingColumn));
        assert_eq!(
            (e.file.as_path(), e.line, e.column.as_deref()),
            (Path::new("series.csv"), Some(1), Some("p3_pa"))
        );
        let e = error(TAPS, &SERIES.replace("0,1000,111,", "0,1000,NaN,"));
        assert!(matches!(e.kind, ErrorKind::NotFinite { .. }));
        assert_eq!((e.line, e.column.as_deref()), (Some(5), Some("p1_pa")));
        // The join: unknown taps, time running back, no baseline, ids out of order.
        let e = error(TAPS, &SERIES.replace("0,2000,", "1,2000,"));
        assert_eq!((e.line, e.column.as_deref()), (Some(6), Some("tap")));
        let e = error(TAPS, &SERIES.replace("0,2000,", "0,500,"));
        assert_eq!((e.line, e.column.as_deref()), (Some(6), Some("t_us")));
        let e = error(TAPS, "tap,t_us,p1_pa,p2_pa,p3_pa\n0,0,1,2,3\n");
        assert!(matches!(e.kind, ErrorKind::Rule(_)));
        let e = error(&TAPS.replace("\n0,256,", "\n1,256,"), SERIES);
        assert_eq!((e.line, e.column.as_deref()), (Some(3), Some("tap")));
    }

    #[test]
    fn retain_keeps_taps_and_series_together() -> Result<(), DatasetError> {
        let two = format!("{TAPS}1,512,1,1,2,1.2000,0,7,1,0.25,-1.5,1.0,2.0,3.0\n");
        let mut data = parse(&two, &format!("{SERIES}1,-5,7,8,9\n"))?;
        data.retain(|t| t.osr == 512);
        assert_eq!(data.taps().len(), 1);
        assert_eq!(data.taps()[0].id, 1);
        assert_eq!(data.taps()[0].offset_mm, [0.25, -1.5]);
        // Cell 1.2's centre (-4.5, 4.5) mm, shifted.
        assert_eq!(data.taps()[0].centroid_mm(), Some([-4.25, 3.0]));
        assert_eq!(data.series()[0].t_us.to_vec(), [-5]);
        Ok(())
    }
}
