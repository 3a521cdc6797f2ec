//! Trains the contact-area MLP on the committed fingertip taps: first the validation search at
//! OSR 256 (repeat 0 only), then per OSR the paper's recipe (both heads) and the chosen
//! configuration; writes the weights, `metrics.json` and `selection.json` to
//! `fixtures/models/contact_mlp/`.
//!
//! Run through `cargo xtask train contact-mlp` (which also draws the plot); arguments:
//! `[WORKSPACE_ROOT] [--epochs N]` (`--epochs` only for quick experiments: no search, paper
//! recipe only, it writes nothing).

mod common;

use std::time::Instant;
use tactile_nets::contact_eval::{self, MODEL_DIR, SEED, SELECTION_FILE, SELECTION_OSR};
use tactile_nets::data::fingertip;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let root = common::workspace_root(&args);
    let epochs: Option<usize> = args
        .iter()
        .position(|a| a == "--epochs")
        .and_then(|i| args.get(i + 1))
        .and_then(|s| s.parse().ok());
    let records = fingertip::load(&root)?;
    let start = Instant::now();
    let mut selection = None;
    let trained = match epochs {
        None => {
            let (chosen, results) = contact_eval::select(&records, SELECTION_OSR, SEED, true)?;
            for (c, e) in &results {
                println!(
                    "validation osr {SELECTION_OSR} {:<32} area {:>6.2} %  exact {:>6.2} %",
                    c.label(),
                    100.0 * e.area_accuracy(),
                    100.0 * e.exact_accuracy()
                );
            }
            println!("chosen: {}", chosen.label());
            selection = Some(contact_eval::selection_file(&results, chosen, SEED));
            contact_eval::train_all(&records, Some(chosen), SEED, true)?
        }
        Some(n) => contact_eval::train_all_with(&records, None, SEED, true, |c| c.epochs = n)?,
    };
    let seconds = start.elapsed().as_secs_f64();
    for t in &trained {
        let e = &t.evaluation;
        println!(
            "osr {:>4} {:<14} area {:>6.2} %  exact {:>6.2} %  cell err {:.3}  centroid err {:.3}  final loss {:.4}",
            t.osr,
            t.label(),
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
        if let Some(selection) = selection {
            let path = root.join(MODEL_DIR).join(SELECTION_FILE);
            std::fs::write(&path, selection.to_json()?)?;
            println!("wrote {}", path.display());
        }
    }
    Ok(())
}
