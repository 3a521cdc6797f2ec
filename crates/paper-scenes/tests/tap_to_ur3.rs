//! `fixtures/scenes/tap-to-ur3.toml` run as written (27 taps, ~20 s of real-time simulated UR3
//! moves): the committed CNN locates as many taps as docs/arm-tap-to-move.md's training-aligned
//! run states (same pad seed, schedule and window, `paper_experiments::tap_run`), every trigger falls
//! inside its tap and every move ends on its grid pose. Needs `$HANDSTACK_PYTHON` (ur-rtde).

mod common;

use common::{root, run_scene, value};
use handstack::Plot;

/// `(correct, n)` of the doc's section whose heading contains `heading`.
fn doc_located(heading: &str) -> (f64, f64) {
    let doc = std::fs::read_to_string(root().join("docs/arm-tap-to-move.md")).expect("doc");
    let section = doc
        .split("\n## ")
        .find(|s| s.lines().next().is_some_and(|h| h.contains(heading)))
        .expect("the section");
    let line = section
        .lines()
        .find(|l| l.starts_with("**Located correctly:"))
        .expect("the located line");
    let nums: Vec<f64> = line
        .trim_start_matches("**Located correctly: ")
        .split(['/', '='])
        .take(2)
        .map(|s| s.trim().parse().expect("a count"))
        .collect();
    (nums[0], nums[1])
}

#[test]
fn tap_scene_moves_the_arm_as_the_committed_run_did() {
    let o = run_scene("tap-to-ur3");
    let (correct, n) = doc_located("where hand-sim's training windows are centred");
    assert_eq!(value(&o, "tap_count"), n);
    assert!((value(&o, "tap_accuracy_pct") - 100.0 * correct / n).abs() < 1e-9);
    assert_eq!(value(&o, "triggers_in_tap"), n);
    let tcp = o.figure("tcp_error_max_m").expect("figure");
    assert_eq!(tcp.met, Some(true), "{tcp:?}");
    let paper = o.figure("tap_accuracy_pct").and_then(|f| f.paper);
    assert_eq!(
        paper,
        Some(93.0),
        "seed 002 §IV-B real-time accuracy beside ours"
    );
    let confusion_total: u32 = o
        .plots
        .iter()
        .find_map(|p| match p {
            Plot::Confusion { counts, .. } => Some(counts.iter().flatten().sum()),
            _ => None,
        })
        .expect("a confusion matrix");
    assert_eq!(f64::from(confusion_total), n);
}
