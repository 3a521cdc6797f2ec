//! The force / weight DNN against the papers' data: the drift check of the committed metrics,
//! and the Table 1 fit. (Its own behaviour is tested in tactile-nets.)

use crate::common::root;
use paper_experiments::data::weights::{self, WeightSample};
use paper_experiments::force_eval::{self, METRICS_FILE, MODEL_DIR, SEED};
use tactile_nets::NetError;
use tactile_nets::metrics::MetricsFile;

/// Table 1 tared on its 0 gf row.
fn table() -> Vec<WeightSample> {
    let rows: Vec<(f64, [f64; 3])> = paper_fixtures::seed000::table1_weight()
        .expect("Table 1 fixture parses")
        .iter()
        .map(|r| (r.weight_gf, r.pressure_hpa))
        .collect();
    weights::tared_table(&rows).expect("Table 1 has a 0 gf row")
}

#[test]
fn committed_metrics_match_a_re_evaluation_of_the_committed_weights() -> Result<(), NetError> {
    let table = table();
    let frames = weights::load_series(&root()).expect("the committed weight series parses");
    let committed = MetricsFile::from_json(&std::fs::read_to_string(
        root().join(MODEL_DIR).join(METRICS_FILE),
    )?)?;
    let models = force_eval::load_committed(&root(), &table)?;
    let fresh = force_eval::metrics_file(&models, &table, &frames, SEED)?;
    assert_eq!(committed.rows.len(), 4);
    let drift = committed.drift(&fresh, 1e-4);
    assert!(drift.is_empty(), "committed metrics drifted: {drift:#?}");
    // The target: the Table 1 fit within 0.5 gf on every row.
    let fit = fresh.row("table1/fit").expect("fit row");
    for s in &table {
        let key = force_eval::row_key(s.weight_gf);
        let gf = fit.values.get(&key).copied().unwrap_or(f64::NAN);
        assert!((gf - f64::from(s.weight_gf)).abs() <= 0.5, "{key}: {gf}");
    }
    Ok(())
}
