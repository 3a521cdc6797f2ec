//! The rig's plain API over the bus simulator's MX-28 (the motor's own tests are
//! dxl-sim's `servo` tests).

use hand_sim::grasp::{GraspRig, ObjectKind, ObjectParams, RigParams};

#[test]
fn rig_rejects_bad_commands_with_typed_errors() {
    let rig = RigParams::default();
    let mut g = GraspRig::new(ObjectParams::table5(ObjectKind::Cube, &rig).unwrap(), rig).unwrap();
    assert!(g.set_torque_limit(1024).is_err());
    assert!(g.set_goal_rad(f64::NAN).is_err());
    assert!(g.step(0.0).is_err());
    assert!(g.step(f64::INFINITY).is_err());
    assert!(g.step(2.0).is_err());
    assert_eq!(g.steps(), 0);
}

#[test]
fn contact_patch_follows_shape_and_force() {
    let rig = RigParams::default();
    let run = |kind, limit| {
        let obj = ObjectParams::table5(kind, &rig).unwrap();
        let mut g = GraspRig::new(obj, rig).unwrap();
        assert!(g.state().patch.cells.is_empty());
        g.set_torque_limit(limit).unwrap();
        g.close().unwrap();
        for _ in 0..2000 {
            g.step(1e-3).unwrap();
        }
        g.state().patch
    };
    // A flat 50 mm face covers the whole 18 × 12 mm pad.
    assert_eq!(run(ObjectKind::Cube, 200).cells.len(), 24);
    // A curved ellipsoid presses a partial patch at a light grip that grows with force (the
    // jelly skin spreads a 5.7 N contact over the whole 18 × 12 mm pad).
    let (small, big) = (
        run(ObjectKind::Ellipsoid, 60),
        run(ObjectKind::Ellipsoid, 390),
    );
    assert!(
        small.cells.len() < big.cells.len() && small.cells.len() < 24,
        "{small:?} {big:?}"
    );
    assert!(big.force_n > small.force_n);
    // The patch force is the settled pad force: 390 / 1023 of 15 N, sent as Goal PWM 337 of 885
    // (0.04 % below 390 / 1023: the 2.0 scale is coarser).
    assert!(
        (big.force_n - 337.0 / 885.0 * 15.0).abs() < 1e-3,
        "{}",
        big.force_n
    );
}
