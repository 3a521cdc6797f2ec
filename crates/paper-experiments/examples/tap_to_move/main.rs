//! Runs the tap-to-move experiment with the committed contact CNN (tactile-nets, paper variant)
//! on the simulated UR3 and writes its report (to the path given, else stdout).
//! `cargo xtask demo tap-to-move` runs it into `docs/arm-tap-to-move.md`.

use paper_experiments::tap_run as run;

use handstack::tap_to_move::TapToMoveConfig;
use std::path::Path;
use std::time::Instant;
use tactile_nets::contact_cnn::ContactCnn;
use ur_sim::TimeScale;

fn main() -> Result<(), String> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let path = run::locator_path(&root);
    let mut cnn = ContactCnn::load(&path).map_err(|e| format!("{}: {e}", path.display()))?;
    let name = format!(
        "the committed contact CNN (`{}`)",
        path.strip_prefix(&root).unwrap_or(&path).display()
    );
    let time_scale = TimeScale::new(run::TIME_SCALE).map_err(|e| e.to_string())?;
    let taps = run::schedule(run::PAD_SEED, run::TAPS_PER_REGION);
    let mut md = format!(
        "# Tap-to-move runs (seed 002 §IV-B)\n\nWritten by `cargo xtask demo tap-to-move`: the same \
         {} taps twice, the window placed two ways (see docs/arm.md). The simulated UR3's \
         controller runs {} × faster than the wall clock; every tap is located and moved to.\n\n",
        taps.len(),
        time_scale.factor()
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
                paper_experiments::cnn_eval::training_centre_frames()
            ),
        ),
    ];
    for (octet, config, window) in plans {
        let started = Instant::now();
        let rows = run::run(
            octet,
            time_scale,
            taps.clone(),
            config,
            &mut cnn,
            run::cnn_window,
        )?;
        md += &run::markdown(&rows, &name, &window, time_scale);
        md += &format!(
            "\nWall time of the run (simulator start, ur_rtde connect, {} cycles): {:.1} s.\n\n",
            rows.len(),
            started.elapsed().as_secs_f64()
        );
    }
    match std::env::args().nth(1) {
        Some(out) => std::fs::write(&out, md).map_err(|e| format!("{out}: {e}")),
        None => {
            print!("{md}");
            Ok(())
        }
    }
}
