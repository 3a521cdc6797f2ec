//! No NaN / inf, no panic: any torque limit, extreme objects, odd steps.

use hand_sim::grasp::{GraspRig, ObjectKind, ObjectParams, RigParams};
use proptest::prelude::*;

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn any_limit_mass_stiffness_and_dt_stay_finite(
        kind in 0usize..6,
        limit in 0u16..=2000,
        mass in 1e-6f64..1e3,
        stiffness in 1e-3f64..1e12,
        dt in 1e-6f64..1.0,
        goal in -10.0f64..10.0,
    ) {
        let rig = RigParams::default();
        let mut obj = ObjectParams::table5(ObjectKind::ALL[kind], &rig).unwrap();
        obj.mass_kg = mass;
        obj.material.stiffness_n_per_m = stiffness;
        let mut g = GraspRig::new(obj, rig).unwrap();
        let set = g.set_torque_limit(limit);
        prop_assert_eq!(set.is_err(), limit > 1023);
        // Position Control Mode takes Goal Position 0…4095 (a turn around the start at π).
        let raw = ((std::f64::consts::PI + goal) / std::f64::consts::TAU * 4096.0).round();
        prop_assert_eq!(g.set_goal_rad(goal).is_err(), !(0.0..=4095.0).contains(&raw));
        for i in 0..200 {
            g.set_lifted(i > 50);
            let s = g.step(dt).unwrap();
            for v in [s.position_rad, s.velocity_rad_s, s.load_fraction, s.current_a,
                      s.grip_force_n, s.slip_m, s.patch.force_n] {
                prop_assert!(v.is_finite(), "{:?}", s);
            }
            // Present Load saturates at ±100 % even when a violent back-drive pushes past stall.
            prop_assert!(s.load_fraction.abs() <= 1.0, "{:?}", s);
        }
    }

    #[test]
    fn invalid_objects_are_rejected(mass in prop_oneof![Just(0.0), Just(-1.0), Just(f64::NAN), Just(f64::INFINITY)]) {
        let rig = RigParams::default();
        let mut obj = ObjectParams::table5(ObjectKind::Cube, &rig).unwrap();
        obj.mass_kg = mass;
        prop_assert!(GraspRig::new(obj, rig).is_err());
    }
}
