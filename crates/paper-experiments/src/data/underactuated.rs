//! The simulated underactuated hand's softness grasps (`fixtures/datasets/underactuated/`,
//! written by `hand-sim`, protocol of seed 001 §3.1, §3.3, §4): `grasps.csv` (one row per
//! grasp: set, object, kind, label) and `train.csv` / `test_regular.csv` / `test_irregular.csv`
//! (the series, 10 Hz from first contact to 14 s after it: 4 FSR forces in N, then 4 distal
//! joint angles in degrees).

use crate::data::fingertip::{data_lines, field};
use hand_traits::Softness;
use std::path::Path;
use tactile_nets::error::NetError;

pub use tactile_nets::softness::{N_VARIABLES, VARIABLE_NAMES};
/// Directory of the dataset below the workspace root.
pub const DATASET_DIR: &str = "fixtures/datasets/underactuated";

/// Which part of the protocol a grasp belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum GraspSet {
    /// 27 model objects × poses, 18 household objects, 6 empty grasps.
    Train,
    /// 24 regular-shape objects.
    TestRegular,
    /// 30 irregular household objects.
    TestIrregular,
}

impl GraspSet {
    /// All sets, in file order.
    pub const ALL: [GraspSet; 3] = [
        GraspSet::Train,
        GraspSet::TestRegular,
        GraspSet::TestIrregular,
    ];

    /// The `set` column's value, which is also the series file's stem.
    pub fn name(self) -> &'static str {
        match self {
            GraspSet::Train => "train",
            GraspSet::TestRegular => "test_regular",
            GraspSet::TestIrregular => "test_irregular",
        }
    }

    fn from_name(s: &str) -> Option<GraspSet> {
        GraspSet::ALL.into_iter().find(|g| g.name() == s)
    }
}

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
    /// The object's overall softness; `None` for the empty grasps (the paper states no label).
    pub label: Option<Softness>,
    /// The series: one sample of [`N_VARIABLES`] readings per 0.1 s, from first contact.
    pub series: Vec<[f32; N_VARIABLES]>,
}

/// The label column's value as a class (`none` → `None`).
pub fn parse_label(s: &str) -> Result<Option<Softness>, String> {
    match s {
        "soft" => Ok(Some(Softness::Soft)),
        "moderate" => Ok(Some(Softness::Moderate)),
        "hard" => Ok(Some(Softness::Hard)),
        "none" => Ok(None),
        other => Err(format!("unknown label `{other}`")),
    }
}

/// Reads every grasp of the committed dataset below the workspace root `root`.
pub fn load(root: &Path) -> Result<Vec<Grasp>, NetError> {
    let dir = root.join(DATASET_DIR);
    let grasps = std::fs::read_to_string(dir.join("grasps.csv"))?;
    let mut series = Vec::new();
    for set in GraspSet::ALL {
        series.push(std::fs::read_to_string(
            dir.join(format!("{}.csv", set.name())),
        )?);
    }
    parse(
        &grasps,
        &series.iter().map(String::as_str).collect::<Vec<_>>(),
    )
}

/// Parses `grasps.csv` and the series files' texts, joined by grasp id. Every grasp must have
/// exactly its `samples` rows.
pub fn parse(grasps_csv: &str, series_csvs: &[&str]) -> Result<Vec<Grasp>, NetError> {
    let mut grasps = Vec::new();
    let mut expected = Vec::new();
    for (line, l) in data_lines(grasps_csv, "grasp,") {
        let f: Vec<&str> = l.split(',').collect();
        if f.len() != 10 {
            return Err(NetError::Data {
                line,
                reason: format!("{} fields, expected 10", f.len()),
            });
        }
        let bad = |reason: String| NetError::Data { line, reason };
        let id: u32 = field(&f, 0, "grasp", line)?;
        if id as usize != grasps.len() {
            return Err(bad(format!("grasp id {id} out of order")));
        }
        grasps.push(Grasp {
            id,
            set: GraspSet::from_name(f[1]).ok_or_else(|| bad(format!("unknown set `{}`", f[1])))?,
            object: f[2].to_owned(),
            kind: f[3].to_owned(),
            label: parse_label(f[7]).map_err(bad)?,
            series: Vec::new(),
        });
        expected.push(field::<usize>(&f, 9, "samples", line)?);
    }
    for text in series_csvs {
        for (line, l) in data_lines(text, "grasp,") {
            let f: Vec<&str> = l.split(',').collect();
            if f.len() != 2 + N_VARIABLES {
                return Err(NetError::Data {
                    line,
                    reason: format!("{} fields, expected {}", f.len(), 2 + N_VARIABLES),
                });
            }
            let id: usize = field(&f, 0, "grasp", line)?;
            let mut sample = [0.0f32; N_VARIABLES];
            for (k, v) in sample.iter_mut().enumerate() {
                *v = field(&f, 2 + k, VARIABLE_NAMES[k], line)?;
            }
            grasps
                .get_mut(id)
                .ok_or_else(|| NetError::Data {
                    line,
                    reason: format!("grasp {id} is not in grasps.csv"),
                })?
                .series
                .push(sample);
        }
    }
    for (g, &n) in grasps.iter().zip(&expected) {
        if g.series.len() != n {
            return Err(NetError::Data {
                line: 0,
                reason: format!(
                    "grasp {} has {} samples, expected {n}",
                    g.id,
                    g.series.len()
                ),
            });
        }
    }
    Ok(grasps)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_and_checks_sample_counts() -> Result<(), NetError> {
        let grasps = "grasp,set,object,kind,shape,size_mm,modulus_pa,label,t1_s,samples\n\
                      0,train,o,model,sphere,65.0,1e4,soft,1.0,2\n";
        let series = "grasp,t_s,f1_n,f2_n,f3_n,f4_n,a1_deg,a2_deg,a3_deg,a4_deg\n\
                      0,0.0,1,2,3,4,5,6,7,8\n0,0.1,1,2,3,4,5,6,7,9\n";
        let g = parse(grasps, &[series])?;
        assert_eq!(g[0].label, Some(Softness::Soft));
        assert_eq!(g[0].series[1][7], 9.0);
        let short =
            "grasp,t_s,f1_n,f2_n,f3_n,f4_n,a1_deg,a2_deg,a3_deg,a4_deg\n0,0.0,1,2,3,4,5,6,7,8\n";
        assert!(matches!(
            parse(grasps, &[short]),
            Err(NetError::Data { .. })
        ));
        let bad = grasps.replace("soft", "squishy");
        assert!(matches!(
            parse(&bad, &[series]),
            Err(NetError::Data { line: 2, .. })
        ));
        Ok(())
    }
}
