//! Seed 002 §IV-B: taps on the ICM-20789 pad (hand-sim, read through the real driver at the
//! scene's pressure mode) trigger on the pressure rise; the 4 × 38 accelerometer / gyroscope
//! window goes to the committed contact CNN; the region it names moves the UR3 (ur-sim's
//! loopback simulator through the real ur_rtde, or the controller at `[arm] host`) to its grid
//! pose. The loop is handstack's `TapToMove` via `paper_experiments::tap_run`, the code path of the
//! `tap_to_move` example that wrote docs/arm-tap-to-move.md.

use super::figure::{Target, measured, paper, target};
use super::{Part, RunContext};
use crate::scene::PaperScene;
use crate::scene::experiments::{Tap, WindowPlacement};
use handstack::RunError;
use handstack::tap_to_move::TapToMoveConfig;
use handstack::{Line, Plot};
use paper_experiments::tap_run::{self, DEPTH_MM, Row};
use tactile_nets::contact_cnn::ContactCnn;

/// Runs the tap-to-UR3 experiment of `scene`.
pub fn run(scene: &PaperScene, exp: &Tap, cx: &RunContext<'_>) -> Result<Part, crate::Error> {
    let path = tap_run::locator_path(&cx.root);
    let mut cnn = ContactCnn::load(&path)?;
    let mut arm = crate::devices::arm::open_in(scene, cx)?;
    let per_region = *exp.taps_per_region.get_ref();
    let pad = crate::devices::pad::open(scene, crate::devices::pad::schedule(scene, per_region))?;
    let config = match exp.window {
        WindowPlacement::Aligned => tap_run::training_aligned(),
        WindowPlacement::Trigger => TapToMoveConfig::default(),
    };
    cx.progress
        .stage("tap: pad → CNN → UR3", pad.taps().len() as u64);
    // All taps in one run_on: the pad's taps follow each other on one simulated clock, as in
    // docs/arm-tap-to-move.md (progress moves once, at the end).
    let rows = tap_run::run_on(&mut arm.arm, pad, config, &mut cnn, tap_run::cnn_window).map_err(
        |reason| RunError::Device {
            device: "tap-to-UR3 loop",
            reason,
        },
    )?;
    cx.progress.advance(rows.len() as u64);
    Ok(part(&rows, &arm.host))
}

fn part(rows: &[Row], host: &str) -> Part {
    let mut part = Part::default();
    let n = rows.len().max(1) as f64;
    let correct = rows.iter().filter(|r| r.located == r.region).count();
    let realtime = paper_fixtures::seed002::constants()
        .and_then(|c| c.value("realtime_accuracy", "%"))
        .ok();
    let f = measured(
        "tap_accuracy_pct",
        &format!(
            "CNN region accuracy, {} taps: {} per region on seeded rows, {DEPTH_MM} mm (arm at \
             {host})",
            rows.len(),
            rows.len() / 9
        ),
        100.0 * correct as f64 / n,
        "%",
    );
    let f = match realtime {
        Some(p) => target(
            paper(f, p, "seed 002 §IV-B (real-time test)"),
            Target::AtLeast(p),
        ),
        None => f,
    };
    part.figures.push(f);
    part.figures
        .push(measured("tap_count", "taps", rows.len() as f64, ""));
    for (region, (right, taps)) in tap_run::per_region(rows).into_iter().enumerate() {
        part.figures.push(measured(
            &format!("tap_region_{region}_pct"),
            &format!("region {region}: {}", tap_run::fraction(right, taps)),
            100.0 * right as f64 / taps.max(1) as f64,
            "%",
        ));
    }
    part.figures.push(measured(
        "triggers_in_tap",
        "triggers inside their tap",
        rows.iter().filter(|r| r.trigger_in_tap).count() as f64,
        "",
    ));
    let mean = |f: fn(&Row) -> f64| rows.iter().map(f).sum::<f64>() / n;
    part.figures.push(measured(
        "locate_mean_us",
        "CNN locate, mean (wall)",
        mean(|r| r.locate_s * 1e6),
        "µs",
    ));
    part.figures.push(measured(
        "window_mean_s",
        "trigger → window complete, mean (pad time)",
        mean(|r| r.window_s),
        "s",
    ));
    part.figures.push(measured(
        "move_mean_s",
        "moveL to the grid pose, mean (controller time, RTDE timestamp)",
        mean(|r| r.move_controller_s),
        "s",
    ));
    part.figures.push(measured(
        "move_wall_mean_s",
        "moveL to the grid pose, mean (wall)",
        mean(|r| r.move_s),
        "s",
    ));
    part.figures.push(measured(
        "cycle_mean_s",
        "cycle: window + locate + move, mean (pad, wall, controller time)",
        mean(|r| r.window_s + r.locate_s + r.move_controller_s),
        "s",
    ));
    part.figures.push(target(
        measured(
            "tcp_error_max_m",
            "final TCP distance from the located pose, max",
            rows.iter().map(|r| r.tcp_error_m).fold(0.0, f64::max),
            "m",
        ),
        Target::AtMost(1e-4),
    ));
    let mut counts = vec![vec![0u32; 9]; 9];
    for r in rows {
        if let Some(c) = counts
            .get_mut(usize::from(r.region))
            .and_then(|row| row.get_mut(usize::from(r.located)))
        {
            *c += 1;
        }
    }
    part.plots.push(Plot::Confusion {
        title: "Tap-to-UR3: region tapped vs located (CNN)".into(),
        labels: (0..9).map(|r| format!("R{r}")).collect(),
        counts,
    });
    part.plots.push(Plot::Lines {
        title: "Tap-to-UR3: cycle time per tap".into(),
        x_label: "tap".into(),
        y_label: "time (s)".into(),
        lines: vec![
            Line {
                label: "trigger → window complete (pad time)".into(),
                points: rows
                    .iter()
                    .enumerate()
                    .map(|(i, r)| (i as f64, r.window_s))
                    .collect(),
            },
            Line {
                label: "moveL (controller time)".into(),
                points: rows
                    .iter()
                    .enumerate()
                    .map(|(i, r)| (i as f64, r.move_controller_s))
                    .collect(),
            },
            Line {
                label: "moveL (wall)".into(),
                points: rows
                    .iter()
                    .enumerate()
                    .map(|(i, r)| (i as f64, r.move_s))
                    .collect(),
            },
        ],
    });
    part
}
