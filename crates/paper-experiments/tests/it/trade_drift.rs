//! Drift check of the committed trade points (`docs/trade/points.csv`, written by `cargo
//! xtask trade`): the cheap, deterministic accuracies — every defuzzifier's error against the
//! fine centroid, every ICM-20789 mode's measured noise — recomputed and compared. CPU costs
//! are wall-clock and are not compared; a mismatch means the controller, the chip model or the
//! driver changed: rerun `cargo xtask trade` and review the diff.

use paper_experiments::trade::{self, CsvRow, defuzz, fixed_point, icm_mode, location};
use std::path::PathBuf;

fn committed() -> Vec<CsvRow> {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..");
    let text = std::fs::read_to_string(root.join(trade::POINTS)).expect("docs/trade/points.csv");
    trade::parse_csv(trade::POINTS.as_ref(), &text).expect("points.csv parses")
}

fn row<'a>(rows: &'a [CsvRow], task: &str, setting: &str) -> &'a CsvRow {
    rows.iter()
        .find(|r| r.task == task && r.setting == setting)
        .unwrap_or_else(|| panic!("no committed point {task} / {setting}"))
}

/// The CSV keeps 6 decimals.
const TOLERANCE: f64 = 2e-6;

#[test]
fn defuzzifier_errors_match_the_committed_points() {
    let rows = committed();
    let errors = defuzz::errors().unwrap();
    assert_eq!(errors.len(), 2 * defuzz::settings().len());
    for (name, precision, err) in errors {
        let r = row(&rows, defuzz::TASK, &defuzz::setting(&name, precision));
        assert!(
            (r.accuracy - err).abs() < TOLERANCE,
            "{name} {precision}: committed {} recomputed {err}",
            r.accuracy
        );
    }
}

#[test]
fn icm_noise_and_osr_frame_periods_match_the_committed_points() {
    let rows = committed();
    for (mode, rms) in icm_mode::noise_pa().unwrap() {
        let r = row(&rows, icm_mode::TASK, &icm_mode::setting(mode));
        assert!(
            (r.accuracy - rms).abs() < TOLERANCE,
            "{mode:?}: {} vs {rms}",
            r.accuracy
        );
        assert_eq!(r.cost_us, f64::from(mode.conversion_time_max_us()));
    }
    // The wire cost of the OSR tasks is the scheduler's bound, not a timing.
    for r in rows.iter().filter(|r| r.task == location::OSR_MLP) {
        let osr: u16 = r.setting.trim_start_matches("OSR ").parse().unwrap();
        assert_eq!(Some(r.cost_us), location::frame_us(osr), "{}", r.setting);
    }
}

/// The fixed-point and float forms of the models on their held-out sets.
#[test]
fn fixed_point_accuracies_match_the_committed_points() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..");
    let rows = committed();
    let mut fresh = fixed_point::mlp_points(&root, false).unwrap();
    fresh.extend(fixed_point::force_points(&root, false).unwrap());
    fresh.extend(fixed_point::cnn_points(&root, false).unwrap());
    fresh.extend(fixed_point::softness_points(&root, false).unwrap());
    assert_eq!(fresh.len(), 26);
    for p in fresh {
        let r = row(&rows, p.task, &p.setting);
        assert!(
            (r.accuracy - p.accuracy).abs() < TOLERANCE,
            "{} / {}: committed {} recomputed {}",
            p.task,
            p.setting,
            r.accuracy,
            p.accuracy
        );
    }
}

#[test]
fn the_committed_fronts_are_the_fronts_of_the_committed_points() {
    let rows = committed();
    for task in trade::tasks() {
        let mine: Vec<&CsvRow> = rows.iter().filter(|r| r.task == task.id).collect();
        assert!(!mine.is_empty(), "no points for {}", task.id);
        assert!(mine.iter().all(|r| r.unit == task.unit), "{}", task.id);
        let xy: Vec<(f64, f64)> = mine.iter().map(|r| (r.cost_us, r.accuracy)).collect();
        let front = trade::pareto_front(&xy, task.better).unwrap();
        let committed: Vec<bool> = mine.iter().map(|r| r.pareto).collect();
        assert_eq!(front, committed, "{}", task.id);
    }
}

#[test]
fn the_committed_file_is_its_rows_written_again() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..");
    let text = std::fs::read_to_string(root.join(trade::POINTS)).expect("docs/trade/points.csv");
    assert_eq!(hand_sim::records::render("", committed()), text);
}
