//! `fixtures/scenes/grasp-table5.toml` run as written (six holds of 123 s simulated): every
//! object's settled torque, its window and settling time, and its peak force are the ones
//! docs/grasping/results.csv states (written by hand-control's `grasp_report` example through the
//! same `paper_experiments::grasp_rig` path and seed), every settled torque lies in its Table 5 band
//! and every object is held.

mod common;

use common::{root, run_scene, value};
use handstack::Plot;

#[test]
fn grasp_scene_reproduces_the_committed_grasp_results() {
    let o = run_scene("grasp-table5");
    let csv = std::fs::read_to_string(root().join("docs/grasping/results.csv")).expect("results");
    let mut header = Vec::new();
    let mut checked = 0;
    for line in csv.lines() {
        let cells: Vec<&str> = line.split(',').collect();
        if header.is_empty() {
            header = cells.iter().map(|s| s.to_string()).collect();
            continue;
        }
        let get = |k: &str| cells[header.iter().position(|h| h == k).expect("column")];
        let name = get("object");
        if o.figure(&format!("{name}_settled_torque")).is_none() {
            continue; // the randomised objects are not in the scene
        }
        let num = |k: &str| get(k).parse::<f64>().expect("number");
        // The CSV rounds: settled to 0.1, times to 0.01 s, forces to 0.01 N.
        assert!(
            (value(&o, &format!("{name}_settled_torque")) - num("settled_torque")).abs() <= 0.051,
            "{name}"
        );
        assert_eq!(
            value(&o, &format!("{name}_window_min")),
            num("window_min"),
            "{name}"
        );
        assert_eq!(
            value(&o, &format!("{name}_window_max")),
            num("window_max"),
            "{name}"
        );
        assert!(
            (value(&o, &format!("{name}_settling_time_s")) - num("settling_time_s")).abs()
                <= 0.0051,
            "{name}"
        );
        assert!(
            (value(&o, &format!("{name}_peak_force_n")) - num("peak_force_n")).abs() <= 0.0051,
            "{name}"
        );
        assert_eq!(
            value(&o, &format!("{name}_held")),
            f64::from(u8::from(get("held") == "true"))
        );
        // Every hold went over Protocol 2.0: the driver's packet counts, as committed.
        for what in ["sent", "received"] {
            let n = value(&o, &format!("{name}_packets_{what}"));
            assert_eq!(n, num(&format!("packets_{what}")), "{name} {what}");
            assert!(n > 12_000.0, "{name}: {n} packets {what}");
        }
        let settled = o.figure(&format!("{name}_settled_torque")).expect("figure");
        assert_eq!(settled.met, Some(true), "{settled:?}");
        checked += 1;
    }
    assert_eq!(checked, 6, "all six Table 5 objects");
    // Traces (one line per object) and the controller's surface (21 × 21).
    let lines: Vec<usize> = o
        .plots
        .iter()
        .filter_map(|p| match p {
            Plot::Lines { lines, .. } => Some(lines.len()),
            _ => None,
        })
        .collect();
    assert_eq!(lines, vec![6, 6]);
    assert!(
        o.plots
            .iter()
            .any(|p| matches!(p, Plot::Surface { z, xs, .. } if z.len() == 21 && xs.len() == 21))
    );
}
