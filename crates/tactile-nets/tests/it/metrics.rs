//! Metrics files: the JSON round trip and the drift check.

use std::collections::BTreeMap;
use tactile_nets::NetError;
use tactile_nets::metrics::{MetricsFile, MetricsRow};

fn file(v: f64) -> MetricsFile {
    MetricsFile {
        model: "m".into(),
        description: "d".into(),
        split: "s".into(),
        seed: 1,
        rows: vec![MetricsRow {
            label: "a".into(),
            values: BTreeMap::from([("acc".to_owned(), v)]),
        }],
    }
}

#[test]
fn json_round_trip_and_drift() -> Result<(), NetError> {
    let f = file(0.5);
    assert_eq!(MetricsFile::from_json(&f.to_json()?)?, f);
    assert!(f.drift(&file(0.5), 0.0).is_empty());
    assert_eq!(f.drift(&file(0.6), 0.01).len(), 1);
    let mut extra = file(0.5);
    extra.rows[0].label = "b".into();
    assert_eq!(f.drift(&extra, 0.0).len(), 2);
    assert!(MetricsFile::from_json("{").is_err());
    Ok(())
}
