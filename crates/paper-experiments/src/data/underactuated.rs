//! The simulated underactuated hand's softness grasps (`fixtures/datasets/underactuated/`,
//! written by `hand-sim`, protocol of seed 001 §3.1, §3.3, §4): `grasps.csv` (one row per
//! grasp: set, object, kind, label, hidden overall class; schema [`GraspRow`]) and `train.csv` /
//! `test_regular.csv` / `test_irregular.csv` / `test_irregular_1000.csv.gz` (the series, 10 Hz from first contact to 14 s after it: 4 FSR forces in
//! N, then 4 distal joint angles in degrees; schema [`SampleRow`]), read into one [`Grasp`]
//! per grasp with its series as a samples × 8 array.

use hand_sim::records::{self, DatasetError, Row};
use hand_sim::underactuated::dataset::{self, GraspRow, SampleRow};
use hand_traits::Softness;
use ndarray::{Array2, ArrayView2};
use std::path::{Path, PathBuf};

pub use hand_sim::underactuated::dataset::Set as GraspSet;
pub use tactile_nets::softness::{N_VARIABLES, VARIABLE_NAMES};
/// The seed `cargo xtask fixtures` generates the dataset from (`hand_sim`'s named streams of it).
pub const SEED: u64 = 1;
/// Directory of the dataset below the workspace root.
pub const DATASET_DIR: &str = "fixtures/datasets/underactuated";

/// One grasp with its series.
#[derive(Debug, Clone, PartialEq)]
pub struct Grasp {
    /// Grasp id.
    pub id: u32,
    /// Its set.
    pub set: GraspSet,
    /// Object name (repeats of a model object share it).
    pub object: String,
    /// `model`, `regular`, `household` or `empty`.
    pub kind: String,
    /// The class label: for a household object the class its fingers' local moduli indicate
    /// (`hand_sim::underactuated::dataset::sensor_class`), else its material's; `None` for the
    /// empty grasps (the paper states no label).
    pub label: Option<Softness>,
    /// The object's hidden overall class (equal to `label` except for household objects whose
    /// fingers meet mostly another class); `None` for the empty grasps.
    pub overall: Option<Softness>,
    /// The local modulus each finger meets, Pa (`e1_pa..e4_pa`).
    pub local_moduli_pa: [f64; 4],
    /// The series: one sample of [`N_VARIABLES`] readings per 0.1 s, from first contact.
    pub series: GraspSeries,
}

/// A grasp's series: samples × [`N_VARIABLES`] (4 FSR forces N, 4 distal angles degrees), in
/// time order, stored row-major.
#[derive(Debug, Clone, PartialEq)]
pub struct GraspSeries(Array2<f32>);

impl GraspSeries {
    /// The series of `samples`, in time order.
    pub fn new(samples: Vec<[f32; N_VARIABLES]>) -> GraspSeries {
        GraspSeries(Array2::from(samples))
    }

    /// The samples × [`N_VARIABLES`] array.
    pub fn view(&self) -> ArrayView2<'_, f32> {
        self.0.view()
    }

    /// Samples in the series.
    pub fn len(&self) -> usize {
        self.0.nrows()
    }

    /// Whether it has no sample.
    pub fn is_empty(&self) -> bool {
        self.0.nrows() == 0
    }

    /// The readings sample after sample (row-major), as the softness net reads a series.
    pub fn as_flattened(&self) -> &[f32] {
        // Built from rows in order, the array is always in standard (row-major) layout.
        self.0.as_slice().unwrap_or_default()
    }

    /// The samples as rows, for the feature and training functions that take them.
    pub fn samples(&self) -> Vec<[f32; N_VARIABLES]> {
        self.as_flattened()
            .chunks_exact(N_VARIABLES)
            .map(|c| core::array::from_fn(|k| c[k]))
            .collect()
    }
}

/// Reads every grasp of the committed dataset below the workspace root `root`.
pub fn load(root: &Path) -> Result<Vec<Grasp>, DatasetError> {
    let dir = root.join(DATASET_DIR);
    let grasps = dir.join("grasps.csv");
    let mut series = Vec::new();
    for set in GraspSet::ALL {
        let path = dir.join(set.series_file());
        let rows = records::read(&path)?;
        series.push((path, Some(set), rows));
    }
    join(&grasps, records::read(&grasps)?, series)
}

/// Grasps hand-sim ran (e.g. a household draw made at training time) as [`load`] reads the
/// committed ones: written to the dataset's CSV forms and parsed back, so they carry the
/// fixtures' rounding. Their ids must run 0, 1, 2… in order.
pub fn from_sim(grasps: &[dataset::Grasp]) -> Result<Vec<Grasp>, DatasetError> {
    let series: Vec<String> = GraspSet::ALL
        .iter()
        .map(|&set| dataset::series_csv(grasps, set))
        .collect();
    let series: Vec<&str> = series.iter().map(String::as_str).collect();
    parse(&dataset::grasps_csv(grasps), &series)
}

/// Parses `grasps.csv` and the series files' texts (named `grasps.csv`, `series0.csv`…),
/// joined by grasp id.
pub fn parse(grasps_csv: &str, series_csvs: &[&str]) -> Result<Vec<Grasp>, DatasetError> {
    let grasps = Path::new("grasps.csv");
    let mut series = Vec::new();
    for (i, text) in series_csvs.iter().enumerate() {
        let path = PathBuf::from(format!("series{i}.csv"));
        let rows = records::parse(&path, text)?;
        series.push((path, None, rows));
    }
    join(grasps, records::parse(grasps, grasps_csv)?, series)
}

/// A series file: its path, the set it holds (if known) and its rows.
type SeriesFile = (PathBuf, Option<GraspSet>, Vec<Row<SampleRow>>);

/// The grasps of `grasps.csv` with their series. Grasps are numbered 0, 1, 2… in file order;
/// every series row names one of them, in its own set's file; every grasp has exactly its
/// `samples` rows.
fn join(
    grasps_file: &Path,
    grasp_rows: Vec<Row<GraspRow>>,
    series: Vec<SeriesFile>,
) -> Result<Vec<Grasp>, DatasetError> {
    let mut heads = Vec::with_capacity(grasp_rows.len());
    for Row { line, record: r } in grasp_rows {
        if r.grasp != heads.len() {
            return Err(DatasetError::value(
                grasps_file,
                line,
                "grasp",
                format!("grasp {} where grasp {} belongs", r.grasp, heads.len()),
            ));
        }
        heads.push((line, r));
    }
    let mut samples: Vec<Vec<[f32; N_VARIABLES]>> = vec![Vec::new(); heads.len()];
    for (file, set, rows) in &series {
        for Row { line, record: r } in rows {
            let Some((_, head)) = heads.get(r.grasp) else {
                return Err(DatasetError::value(
                    file,
                    *line,
                    "grasp",
                    format!("grasp {} is not in grasps.csv", r.grasp),
                ));
            };
            if set.is_some_and(|set| set != head.set) {
                return Err(DatasetError::value(
                    file,
                    *line,
                    "grasp",
                    format!("grasp {} belongs to {}", r.grasp, head.set.name()),
                ));
            }
            samples[r.grasp].push(r.readings());
        }
    }
    heads
        .into_iter()
        .zip(samples)
        .map(|((line, r), series)| {
            if series.len() != r.samples {
                return Err(DatasetError::value(
                    grasps_file,
                    line,
                    "samples",
                    format!(
                        "grasp {} has {} samples in its series, not {}",
                        r.grasp,
                        series.len(),
                        r.samples
                    ),
                ));
            }
            let id = u32::try_from(r.grasp)
                .map_err(|_| DatasetError::value(grasps_file, line, "grasp", "too large"))?;
            Ok(Grasp {
                id,
                set: r.set,
                object: r.object,
                kind: r.kind,
                label: r.label,
                overall: r.overall,
                local_moduli_pa: [r.e1_pa.0, r.e2_pa.0, r.e3_pa.0, r.e4_pa.0],
                series: GraspSeries::new(series),
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use hand_sim::records::ErrorKind;

    const GRASPS: &str = "grasp,set,object,kind,shape,size_mm,modulus_pa,label,overall,\
                          e1_pa,e2_pa,e3_pa,e4_pa,t1_s,samples\n\
                          0,train,o,model,sphere,65.0,1.0000e4,soft,soft,\
                          1.0000e4,1.0000e4,1.0000e4,1.0000e4,1.000,2\n";
    const SERIES: &str = "grasp,t_s,f1_n,f2_n,f3_n,f4_n,a1_deg,a2_deg,a3_deg,a4_deg\n\
                          0,0.0,1,2,3,4,5,6,7,8\n0,0.1,1,2,3,4,5,6,7,9\n";

    #[test]
    fn parses_and_checks_sample_counts() -> Result<(), DatasetError> {
        let g = parse(GRASPS, &[SERIES])?;
        assert_eq!(g[0].label, Some(Softness::Soft));
        assert_eq!(g[0].series.view().dim(), (2, N_VARIABLES));
        assert_eq!(g[0].series.view()[[1, 7]], 9.0);
        assert_eq!(g[0].series.as_flattened()[15], 9.0);
        assert_eq!(g[0].series.samples()[1][7], 9.0);
        let short = &SERIES[..SERIES.rfind("0,0.1").unwrap_or(0)];
        let e = parse(GRASPS, &[short]).expect_err("a sample short");
        assert_eq!((e.line, e.column.as_deref()), (Some(2), Some("samples")));
        let e =
            parse(&GRASPS.replace("soft,soft", "squishy,soft"), &[SERIES]).expect_err("a label");
        assert_eq!((e.line, e.column.as_deref()), (Some(2), Some("label")));
        let e = parse(GRASPS, &[&SERIES.replace("\n0,0.1,", "\n1,0.1,")]).expect_err("grasp 1");
        assert_eq!((e.line, e.column.as_deref()), (Some(3), Some("grasp")));
        let e = parse(GRASPS, &[&SERIES.replace(",7,9\n", ",7,NaN\n")]).expect_err("NaN");
        assert!(matches!(e.kind, ErrorKind::NotFinite { .. }));
        assert_eq!(
            (e.file.as_path(), e.line, e.column.as_deref()),
            (Path::new("series0.csv"), Some(3), Some("a4_deg"))
        );
        let e = parse(&GRASPS.replace(",kind,", ",type,"), &[SERIES]).expect_err("a column");
        assert!(matches!(&e.kind, ErrorKind::WrongColumn { found } if found == "type"));
        Ok(())
    }
}
