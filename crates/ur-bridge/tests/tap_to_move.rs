//! The tap-to-move run (examples/tap_to_move/run.rs) for all 9 regions: every trigger inside its
//! tap, the named region moved to, the final TCP within 0.1 mm of its grid pose.

#[path = "../examples/tap_to_move/run.rs"]
mod run;

#[test]
fn every_region_moves_the_arm_to_its_grid_pose() {
    let rows = run::run(21).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(rows.len(), 9);
    for (k, r) in rows.iter().enumerate() {
        assert_eq!(usize::from(r.region), k, "one tap per region, in order");
        assert_eq!(r.located, r.region);
        assert!(
            r.trigger_in_tap,
            "region {k}: trigger {} s after the press began",
            r.trigger_after_press_s
        );
        // The trigger is the first of the window's last 19 frames: 18 frame periods at 30 Hz.
        assert!((r.window_s - 18.0 / 30.0).abs() < 1e-3, "{}", r.window_s);
        assert!(r.tcp_error_m < 1e-4, "region {k}: {} m", r.tcp_error_m);
    }
    println!("{}", run::markdown(&rows));
}
