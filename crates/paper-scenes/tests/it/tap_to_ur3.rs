//! `fixtures/scenes/tap-to-ur3.toml` run as written (90 taps, 10 per region on seeded rows; the
//! simulated UR3 at time scale 10, ~15 s): the committed CNN locates as many taps, region by
//! region, as docs/arm-tap-to-move.md's training-aligned run states (same pad seed, schedule and
//! window, `paper_experiments::tap_run`), every trigger falls inside its tap and every move ends
//! on its grid pose, in controller time as long as at real time. Needs `$HANDSTACK_PYTHON`
//! (ur-rtde).

use crate::common;

use common::{root, run_scene, value};
use handstack::Plot;

/// The doc's section whose heading contains `heading`.
fn doc_section(heading: &str) -> String {
    let doc = std::fs::read_to_string(root().join("docs/arm-tap-to-move.md")).expect("doc");
    doc.split("\n## ")
        .find(|s| s.lines().next().is_some_and(|h| h.contains(heading)))
        .expect("the section")
        .to_owned()
}

/// `(correct, n)` of the doc's section whose heading contains `heading`.
fn doc_located(heading: &str) -> (f64, f64) {
    let section = doc_section(heading);
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

/// The doc's per-region row (`| located | 9 / 10 | … |`) as percentages.
fn doc_per_region(heading: &str) -> Vec<f64> {
    let section = doc_section(heading);
    let line = section
        .lines()
        .find(|l| l.starts_with("| located |"))
        .expect("the per-region row");
    line.split('|')
        .skip(2)
        .filter(|c| c.contains('/'))
        .map(|c| {
            let (a, b) = c.split_once('/').expect("n / m");
            let (a, b): (f64, f64) = (a.trim().parse().unwrap(), b.trim().parse().unwrap());
            100.0 * a / b
        })
        .collect()
}

const ALIGNED: &str = "where hand-sim's training windows are centred";

#[test]
fn tap_scene_moves_the_arm_as_the_committed_run_did() {
    let o = {
        let _arm = crate::common::time_scaled_arm();
        run_scene("tap-to-ur3")
    };
    let (correct, n) = doc_located(ALIGNED);
    assert!(n >= 90.0, "at least 10 taps per region");
    let per_region = doc_per_region(ALIGNED);
    assert_eq!(per_region.len(), 9);
    for (r, pct) in per_region.iter().enumerate() {
        assert!(
            (value(&o, &format!("tap_region_{r}_pct")) - pct).abs() < 1e-9,
            "region {r}"
        );
    }
    // Moves measured on the controller's clock: the 0.69–0.77 s profiles plus the handshake
    // and the client's poll (at most 10 × 8 ms at the scene's time scale), at a tenth of the
    // wall time.
    let ctrl = value(&o, "move_mean_s");
    assert!(ctrl > 0.69 && ctrl < 0.77 + 0.12, "{ctrl}");
    assert!(value(&o, "move_wall_mean_s") < ctrl / 5.0);
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
