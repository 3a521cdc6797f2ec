//! The MX-28 model alone and the rig's plain API.

use hand_sim::grasp::servo::{LoadLinearisation, Mx28, ServoParams};
use hand_sim::grasp::{GraspRig, ObjectKind, ObjectParams, RigParams};
use hand_traits::Faults;

#[test]
fn free_servo_reaches_goal_at_moving_speed() {
    let p = ServoParams::default();
    let mut s = Mx28::new(p).unwrap();
    s.set_goal_rad(0.5).unwrap();
    for _ in 0..1000 {
        s.step(1e-3, LoadLinearisation::default());
    }
    // After 1 s the set-point has moved moving_speed · 1 s; the servo trails it slightly.
    let v = s.velocity_rad_s();
    assert!(
        (v - p.moving_speed_rad_s).abs() < 0.01 * p.moving_speed_rad_s,
        "{v}"
    );
    for _ in 0..5000 {
        s.step(1e-3, LoadLinearisation::default());
    }
    assert!(
        (s.position_rad() - 0.5).abs() < 1e-3,
        "{}",
        s.position_rad()
    );
    assert!(s.load_fraction().abs() < 0.05);
}

#[test]
fn stalled_load_equals_the_limit_and_overload_needs_ninety_percent() {
    let stall = LoadLinearisation {
        torque_nm: 100.0,
        stiffness_nm_per_rad: 0.0,
        damping_nm_s_per_rad: 1e6,
    };
    for (limit, trips) in [(400_u16, false), (900, false), (930, true), (1023, true)] {
        let mut s = Mx28::new(ServoParams::default()).unwrap();
        s.set_torque_limit(limit).unwrap();
        s.set_goal_rad(1.0).unwrap();
        for _ in 0..3000 {
            s.step(1e-3, stall);
        }
        assert_eq!(
            s.faults().contains(Faults::OVERLOAD),
            trips,
            "limit {limit}"
        );
        if !trips {
            let want = f64::from(limit) / 1023.0;
            assert!(
                (s.load_fraction() - want).abs() < 1e-3,
                "{}",
                s.load_fraction()
            );
            assert_eq!(s.present_load_raw(), limit);
        }
    }
}

#[test]
fn overload_shuts_torque_off_until_reboot() {
    let mut s = Mx28::new(ServoParams::default()).unwrap();
    s.set_goal_rad(1.0).unwrap();
    let stall = LoadLinearisation {
        torque_nm: 100.0,
        stiffness_nm_per_rad: 0.0,
        damping_nm_s_per_rad: 1e6,
    };
    for _ in 0..2000 {
        s.step(1e-3, stall);
    }
    assert!(s.faults().contains(Faults::OVERLOAD) && !s.torque_enabled());
    assert_eq!(s.current_a(), 0.0);
    assert!(s.set_torque_enabled(true).is_err());
    s.reboot();
    assert!(s.faults().is_empty() && !s.torque_enabled());
    s.set_torque_enabled(true).unwrap();
}

#[test]
fn back_driven_load_sets_the_direction_bit() {
    let mut s = Mx28::new(ServoParams::default()).unwrap();
    s.set_goal_rad(-1.0).unwrap();
    for _ in 0..100 {
        s.step(1e-3, LoadLinearisation::default());
    }
    assert!(s.load_fraction() < 0.0);
    assert_ne!(s.present_load_raw() & 1 << 10, 0);
}

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
    // The patch force is the settled pad force: 390 / 1023 of 15 N.
    assert!(
        (big.force_n - 390.0 / 1023.0 * 15.0).abs() < 0.01,
        "{}",
        big.force_n
    );
}
