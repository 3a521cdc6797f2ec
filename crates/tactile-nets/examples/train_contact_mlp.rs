//! Trains the contact-area MLP (one model per OSR and head) on the committed fingertip taps and
//! writes the weights and metrics to `fixtures/models/contact_mlp/`.
//!
//! Run through `cargo xtask train contact-mlp` (which also draws the plot); arguments:
//! `[WORKSPACE_ROOT] [--epochs N]` (`--epochs` only for quick experiments: it writes nothing).

use std::path::PathBuf;
use std::time::Instant;
use tactile_nets::contact_eval::{self, MODEL_DIR, SEED};
use tactile_nets::data::fingertip;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let root = args
        .first()
        .filter(|a| !a.starts_with("--"))
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../.."));
    let epochs: Option<usize> = args
        .iter()
        .position(|a| a == "--epochs")
        .and_then(|i| args.get(i + 1))
        .and_then(|s| s.parse().ok());
    let records = fingertip::load(&root)?;
    let start = Instant::now();
    let trained = match epochs {
        None => contact_eval::train_all(&records, SEED, true)?,
        Some(n) => contact_eval::train_all_with(&records, SEED, true, |c| c.epochs = n)?,
    };
    let seconds = start.elapsed().as_secs_f64();
    for t in &trained {
        let e = &t.evaluation;
        println!(
            "osr {:>4} {:<12} area {:>6.2} %  exact {:>6.2} %  cell err {:.3}  centroid err {:.3}  final loss {:.4}",
            t.osr,
            t.model.head().name(),
            100.0 * e.area_accuracy(),
            100.0 * e.exact_accuracy(),
            e.mean_cell_error(),
            e.mean_centroid_error(),
            t.log.epoch_loss.last().copied().unwrap_or(f32::NAN),
        );
    }
    println!("training time: {seconds:.1} s for {} models", trained.len());
    if epochs.is_none() {
        for path in contact_eval::save_all(&root.join(MODEL_DIR), &trained, SEED)? {
            println!("wrote {}", path.display());
        }
    }
    Ok(())
}
