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
use tactile_nets::softness_features::Features;

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
    // Our variant: inputs chosen on the validation split of the training objects.
    let mut validation = Vec::new();
    for features in Features::ALL {
        let acc = softness_eval::validate_features(&grasps, features)?;
        println!("validation {:<16} {:>5.1} %", features.name(), 100.0 * acc);
        validation.push((features.name().to_owned(), acc));
    }
    let chosen = Features::CANDIDATES
        .into_iter()
        .fold(None::<(Features, f64)>, |best, f| {
            let acc = validation
                .iter()
                .find(|(n, _)| n == f.name())
                .map_or(0.0, |v| v.1);
            match best {
                Some((_, b)) if b >= acc => best,
                _ => Some((f, acc)),
            }
        })
        .map(|(f, _)| f)
        .ok_or("no candidate")?;
    let mut ours = Vec::new();
    for seed in SEEDS {
        let run = softness_eval::train_ours(&grasps, chosen, seed)?;
        let e = &run.evaluation;
        println!(
            "ours {} seed {seed}: train {:>5.1} %  regular {:>5.1} %  irregular {:>5.1} %  mse {:.4}  {:>6.2} s",
            chosen.name(),
            100.0 * e.train.accuracy(),
            100.0 * e.regular.accuracy(),
            100.0 * e.irregular.accuracy(),
            e.train_mse,
            run.seconds,
        );
        ours.push(run);
    }
    if !args.iter().any(|a| a == "--dry-run") {
        let dir = root.join(MODEL_DIR);
        let mut written = softness_eval::save_all(&dir, &runs)?;
        written.extend(softness_eval::save_ours(&dir, &ours, &validation)?);
        for path in written {
            println!("wrote {}", path.display());
        }
    }
    Ok(())
}
