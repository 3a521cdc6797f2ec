//! Every committed dataset file is its schema's rendering of its own rows: reading a file
//! through its record type and writing the records back gives the committed bytes. So the
//! writers' number formats and the readers' schema are one (the simulation itself is checked
//! by `cargo xtask fixtures --check`).

use hand_sim::fingertip::dataset::{
    SERIES_PREAMBLE, SeriesRow, TAPS_PREAMBLE, TapRow, WEIGHTS_PREAMBLE, WeightRow,
};
use hand_sim::imu_pad::dataset::{ImuTapRow, preamble};
use hand_sim::records::{self, DatasetError, ErrorKind, Schema};
use hand_sim::underactuated::dataset::{GraspRow, SampleRow, Set};
use std::path::{Path, PathBuf};

fn dataset(file: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../fixtures/datasets")
        .join(file)
}

/// Reads `file` as `R` and renders it again after `preamble` (gzipped again for a `.gz` file).
fn round_trip<R: Schema>(file: &str, preamble: &str) -> Result<usize, DatasetError> {
    let path = dataset(file);
    let committed = std::fs::read(&path).expect("the committed dataset");
    let rows = records::read::<R>(&path)?;
    let n = rows.len();
    let rendered = records::render(preamble, rows.into_iter().map(|r| r.record));
    let rendered = if file.ends_with(".gz") {
        records::gzip(&rendered)
    } else {
        rendered.into_bytes()
    };
    assert!(rendered == committed, "{file} does not round-trip");
    Ok(n)
}

#[test]
fn fingertip_files_round_trip() -> Result<(), DatasetError> {
    assert_eq!(
        round_trip::<TapRow>("fingertip/taps.csv", TAPS_PREAMBLE)?,
        2040
    );
    assert_eq!(
        round_trip::<SeriesRow>("fingertip/series.csv", SERIES_PREAMBLE)?,
        79968
    );
    assert_eq!(
        round_trip::<WeightRow>("fingertip/weights.csv", WEIGHTS_PREAMBLE)?,
        6966
    );
    Ok(())
}

#[test]
fn imu_pad_file_round_trips() -> Result<(), DatasetError> {
    assert_eq!(
        round_trip::<ImuTapRow>("imu_pad/taps.csv", &preamble(2))?,
        2880
    );
    assert_eq!(ImuTapRow::columns().len(), 7 + 4 * 38);
    Ok(())
}

#[test]
fn underactuated_files_round_trip() -> Result<(), DatasetError> {
    assert_eq!(
        round_trip::<GraspRow>("underactuated/grasps.csv", "")?,
        1213
    );
    let mut samples = 0;
    for set in Set::ALL {
        samples += round_trip::<SampleRow>(&format!("underactuated/{}", set.series_file()), "")?;
    }
    assert_eq!(samples, 1213 * 141);
    Ok(())
}

#[test]
fn an_unknown_name_is_an_error_naming_its_column() {
    let text = "grasp,set,object,kind,shape,size_mm,modulus_pa,label,overall,e1_pa,e2_pa,e3_pa,e4_pa,t1_s,samples\n\
                0,train,o,model,sphere,65.0,1.0000e4,soft,soft,1.0000e4,1.0000e4,1.0000e4,1.0000e4,1.000,2\n";
    let parse = |text: &str| records::parse::<GraspRow>(Path::new("grasps.csv"), text);
    let rows = parse(text).expect("a good row");
    assert_eq!(rows[0].record.label, Some(hand_traits::Softness::Soft));
    for (bad, column) in [(",squishy,", "label"), (",training,", "set")] {
        let good = if column == "label" {
            ",soft,"
        } else {
            ",train,"
        };
        let e = parse(&text.replace(good, bad)).expect_err("an unknown name");
        assert!(matches!(e.kind, ErrorKind::Value(_)), "{e}");
        assert_eq!(
            (e.line, e.column.as_deref()),
            (Some(2), Some(column)),
            "{e}"
        );
    }
}
