//! Trains the softness classifier (seed 001) with Levenberg–Marquardt and with Adam, one model
//! per seed, on the committed underactuated-hand grasps, and writes the weights, `metrics.json`
//! and `training.json` to `fixtures/models/softness/`.
//!
//! Run through `cargo xtask train softness` (which also draws the figures and writes the
//! report section); arguments: `[WORKSPACE_ROOT] [--dry-run]` (`--dry-run` writes nothing).

mod common;

use indicatif::{ProgressBar, ProgressStyle};
use tactile_nets::data::underactuated;
use tactile_nets::softness_eval::{self, MODEL_DIR, OPTIMISERS, SEEDS};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let root = common::workspace_root(&args);
    let grasps = underactuated::load(&root)?;
    let bar = ProgressBar::new((OPTIMISERS.len() * SEEDS.len()) as u64);
    if let Ok(style) =
        ProgressStyle::with_template("{prefix:>12} [{bar:30}] {pos}/{len} models {msg}")
    {
        bar.set_style(style.progress_chars("=> "));
    }
    bar.set_prefix("softness");
    let mut runs = Vec::new();
    let only: Option<usize> = std::env::var("SOFTNESS_ONLY")
        .ok()
        .and_then(|s| s.parse().ok());
    for optimiser in OPTIMISERS
        .into_iter()
        .skip(only.unwrap_or(0))
        .take(if only.is_some() { 1 } else { 2 })
    {
        for seed in SEEDS {
            bar.set_message(format!("{} seed {seed}", optimiser().name()));
            let run = softness_eval::train_one(&grasps, optimiser(), seed)?;
            let e = &run.evaluation;
            let stop = run.report.as_ref().map_or("", |r| r.stop.name());
            bar.suspend(|| println!(
                "{:<4} seed {seed}: train {:>5.1} %  regular {:>5.1} %  irregular {:>5.1} %  mse {:.4}  {:>6.2} s  ({stop}, {} evaluations)",
                run.optimiser,
                100.0 * e.train.accuracy(),
                100.0 * e.regular.accuracy(),
                100.0 * e.irregular.accuracy(),
                e.train_mse,
                run.seconds,
                run.report.as_ref().map_or(0, |r| r.curve.len()),
            ));
            runs.push(run);
            bar.inc(1);
        }
    }
    bar.finish();
    if !args.iter().any(|a| a == "--dry-run") {
        for path in softness_eval::save_all(&root.join(MODEL_DIR), &runs)? {
            println!("wrote {}", path.display());
        }
    }
    Ok(())
}
