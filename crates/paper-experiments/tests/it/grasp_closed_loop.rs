//! Closed-loop holds in simulated time: the fuzzy grasp loop, fed by
//! hand-sim's barometric fingertip through the real MS5611 driver, closes hand-sim's MX-28 rig
//! on each seed 000 Table 5 object (bands read from `paper-fixtures`) and on 20 randomised
//! objects, lifts at 3 s and holds 120 s: no slip, no damage, no fault, settled torque inside
//! the object's range.

use paper_experiments::data::grasp_results;
use paper_experiments::grasp_rig as support;

use hand_control::grasp_loop::{Mode, TorqueBand};
use hand_sim::grasp::{ObjectKind, ObjectParams, RigParams, random_objects};
use paper_fixtures::seed000::table5_grasp_torque;
use support::Outcome;

/// The committed `docs/grasping/results.csv` row for `name`: (settled torque, peak force N).
fn committed(name: &str) -> (f32, f64) {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let rows = grasp_results::load(&root).expect("committed results (grasp_report example)");
    let row = rows
        .iter()
        .find(|r| r.object == name)
        .unwrap_or_else(|| panic!("{name} not in results.csv"));
    (row.settled_torque.0, row.peak_force_n.0)
}

fn check(o: &Outcome) {
    // The docs' table is what these runs give (regenerate with the grasp_report example).
    let (settled, peak) = committed(&o.name);
    assert!(
        (o.settled_raw - settled).abs() <= 0.1 && (o.peak_force_n - peak).abs() <= 0.01,
        "{}: {} / {} N drifted from docs/grasping/results.csv {settled} / {peak} N",
        o.name,
        o.settled_raw,
        o.peak_force_n
    );
    let (lo, hi) = o.band;
    assert!(
        !o.slipped && !o.damaged && !o.dropped,
        "{}: slip {:.2e} m, damaged {}, dropped {}",
        o.name,
        o.slip_m,
        o.damaged,
        o.dropped
    );
    assert_eq!(o.faults, 0, "{}: faults reported", o.name);
    assert_eq!(o.mode, Mode::Grasp, "{}", o.name);
    assert_eq!(o.missed_ticks, 0, "{}", o.name);
    // 10 ms cycles from t = 0 to 123 s: every one logged.
    assert_eq!(o.cycles, 12_300, "{}", o.name);
    assert!(
        f32::from(lo) <= o.settled_raw && o.settled_raw <= f32::from(hi),
        "{}: settled {} outside {lo}…{hi}",
        o.name,
        o.settled_raw
    );
    assert!(
        o.window_raw.0 >= lo && o.window_raw.1 <= hi,
        "{}: {:?} leaves {lo}…{hi}",
        o.name,
        o.window_raw
    );
    // No limit cycle: the last 10 s stay within ±2 % of the scale (a 10 Hz rate filter gave a
    // 14 Hz cycle of ±60 counts on a soft random cone; see docs/grasping.md).
    assert!(
        o.window_raw.1 - o.window_raw.0 <= 2 * support::SETTLE_TOL_RAW as u16,
        "{}: torque swings {:?}",
        o.name,
        o.window_raw
    );
    // Settled well before the lift at 3 s plus the hold: the torque does not wander.
    assert!(
        o.settling_time_s < 5.0,
        "{}: settles at {} s",
        o.name,
        o.settling_time_s
    );
    assert!(
        o.final_pressure_pa > 50.0,
        "{}: no contact pressure",
        o.name
    );
}

#[test]
fn table5_objects_held_two_minutes() {
    let rig = RigParams::default();
    for row in table5_grasp_torque().expect("Table 5 fixture") {
        let kind = ObjectKind::from_name(&row.object).expect("a Table 5 object");
        let (lo, hi) = (row.torque_min as u16, row.torque_max as u16);
        let object = ObjectParams::calibrated(kind, lo, hi, &rig).expect("calibrates");
        let band = TorqueBand::new(lo, hi).expect("Table 5 band");
        let (o, _, _) = support::hold(&row.object, object, band, 7).expect("held");
        check(&o);
    }
}

#[test]
fn twenty_random_objects_held_two_minutes() {
    let rig = RigParams::default();
    for (i, r) in random_objects(42, 20, &rig)
        .expect("objects")
        .into_iter()
        .enumerate()
    {
        let band = TorqueBand::new(r.range.min, r.range.max).expect("derived band");
        let (o, _, _) =
            support::hold(&r.params.name.clone(), r.params, band, 100 + i as u64).expect("held");
        check(&o);
    }
}
