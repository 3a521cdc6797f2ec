//! Runs the tap-to-move experiment with the committed contact CNN (tactile-nets, paper variant)
//! on the simulated UR3 and writes its report (to the path given, else stdout).
//! `cargo xtask demo tap-to-move` runs it into `docs/arm-tap-to-move.md`.

use paper_experiments::tap_run as run;

use paper_experiments::cnn_eval::{MODEL_DIR, model_file};
use std::path::Path;
use tactile_nets::contact_cnn::{ContactCnn, Variant};
use ur_bridge::tap_to_move::TapToMoveConfig;

fn main() -> Result<(), String> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let path = root.join(MODEL_DIR).join(model_file(Variant::Paper));
    let mut cnn = ContactCnn::load(&path).map_err(|e| format!("{}: {e}", path.display()))?;
    let name = format!(
        "the committed contact CNN (`{}`)",
        path.strip_prefix(&root).unwrap_or(&path).display()
    );
    let mut md = String::from(
        "# Tap-to-move runs (seed 002 §IV-B)\n\nWritten by `cargo xtask demo tap-to-move`: the same \
         27 taps twice, the window placed two ways (see docs/arm.md).\n\n",
    );
    let plans = [
        (
            31,
            TapToMoveConfig::default(),
            "window centred on the pressure trigger (19 + 19 frames)".to_string(),
        ),
        (
            32,
            run::training_aligned(),
            format!(
                "window centred {} frames after the trigger, where hand-sim's training windows are centred",
                run::training_centre_frames()
            ),
        ),
    ];
    for (octet, config, window) in plans {
        let rows = run::run(
            octet,
            run::schedule(&run::ROUNDS),
            config,
            &mut cnn,
            run::cnn_window,
        )?;
        md += &run::markdown(&rows, &name, &window);
        md += "\n";
    }
    match std::env::args().nth(1) {
        Some(out) => std::fs::write(&out, md).map_err(|e| format!("{out}: {e}")),
        None => {
            print!("{md}");
            Ok(())
        }
    }
}
