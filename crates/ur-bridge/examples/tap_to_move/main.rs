//! Runs the tap-to-move experiment with the committed contact CNN (tactile-nets, paper variant)
//! on the simulated UR3 and writes its report (to the path given, else stdout).
//! `cargo xtask demo tap-to-move` runs it into `docs/arm-tap-to-move.md`.

mod run;

use std::path::Path;
use tactile_nets::cnn_eval::{MODEL_DIR, model_file};
use tactile_nets::contact_cnn::{ContactCnn, Variant};

fn main() -> Result<(), String> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let path = root.join(MODEL_DIR).join(model_file(Variant::Paper));
    let mut cnn = ContactCnn::load(&path).map_err(|e| format!("{}: {e}", path.display()))?;
    let rows = run::run(31, run::schedule(&run::ROUNDS), &mut cnn, run::cnn_window)?;
    let md = run::markdown(
        &rows,
        &format!(
            "the committed contact CNN (`{}`)",
            path.strip_prefix(&root).unwrap_or(&path).display()
        ),
    );
    match std::env::args().nth(1) {
        Some(out) => std::fs::write(&out, md).map_err(|e| format!("{out}: {e}")),
        None => {
            print!("{md}");
            Ok(())
        }
    }
}
