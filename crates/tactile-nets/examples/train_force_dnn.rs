//! Trains the force / weight DNN (Table 1 fit, its 13 leave-one-out models, the simulated
//! series model) and writes the weights, metrics and training curves to
//! `fixtures/models/force_dnn/`.
//!
//! Run through `cargo xtask train force-dnn` (which also draws the curve and writes the docs
//! section); argument: `[WORKSPACE_ROOT]`.

mod common;

use std::time::Instant;
use tactile_nets::data::weights;
use tactile_nets::force_eval::{self, MODEL_DIR, SEED};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let root = common::workspace_root(&args);
    let rows: Vec<(f64, [f64; 3])> = paper_fixtures::seed000::table1_weight()?
        .iter()
        .map(|r| (r.weight_gf, r.pressure_hpa))
        .collect();
    let table = weights::tared_table(&rows)?;
    let frames = weights::load_series(&root)?;
    let start = Instant::now();
    let models = force_eval::train_all(&table, &frames, SEED, true)?;
    let seconds = start.elapsed().as_secs_f64();
    let metrics = force_eval::metrics_file(&models, &table, &frames, SEED)?;
    for row in &metrics.rows {
        let v = |k: &str| row.values.get(k).copied().unwrap_or(f64::NAN);
        println!(
            "{:<14} mean |err| {:>7.3} gf  max |err| {:>7.3} gf  rmse {:>7.3} gf",
            row.label,
            v("mean_abs_error_gf"),
            v("max_abs_error_gf"),
            v("rmse_gf")
        );
    }
    println!(
        "training time: {seconds:.1} s for {} models",
        models.loo.len() + 2
    );
    for path in force_eval::save_all(&root.join(MODEL_DIR), &models, &table, &metrics)? {
        println!("wrote {}", path.display());
    }
    Ok(())
}
