//! No NaN or infinity, and no panic, at the extremes: stiffness 0 … huge, objects of no size or
//! too big, odd time steps, any seed. Invalid values give a typed `SimError::Config`.

use hand_sim::SimError;
use hand_sim::scene::Model;
use hand_sim::underactuated::{Material, ObjectConfig, Shape, Underactuated, UnderactuatedConfig};
use hand_traits::TactileSource;
use proptest::prelude::*;

fn modulus() -> impl Strategy<Value = f64> {
    prop_oneof![
        Just(0.0),
        Just(f64::MIN_POSITIVE),
        Just(1e300),
        Just(f64::MAX),
        (0.0f64..12.0).prop_map(|e| 10f64.powf(e)),
    ]
}

fn shape() -> impl Strategy<Value = Shape> {
    prop_oneof![
        Just(Shape::Rectangular),
        Just(Shape::Cylinder),
        Just(Shape::Sphere)
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(32))]

    #[test]
    fn readings_stay_finite_and_in_range(
        seed in any::<u64>(),
        e in modulus(),
        local in prop::array::uniform4(prop_oneof![Just(0.0), Just(1e200), 0.01f64..100.0]),
        size in 0.0f64..=130.0,
        shape in shape(),
        step_ms in 0.1f64..1000.0,
        times in prop::collection::vec(any::<u64>(), 1..4),
    ) {
        let config = UnderactuatedConfig {
            step_ms: step_ms.max(5.0),
            duration_s: 2.0,
            approach_timeout_s: 30.0,
            object: ObjectConfig {
                shape, size_mm: size, material: Material::Sponge, modulus_pa: Some(e),
                local_modulus_factor: local, ..ObjectConfig::default()
            },
            ..UnderactuatedConfig::default()
        };
        let mut hand = Underactuated::new(&config, seed).unwrap();
        let mut sorted = times;
        sorted.sort_unstable();
        for t in sorted {
            hand.step_to(t).unwrap();
            let frame = hand.read_frame().unwrap();
            let max_force = config.sensors.fsr.max_force_n as f32;
            for f in frame.force_n {
                prop_assert!(f.is_finite() && (0.0..=max_force).contains(&f), "{f}");
            }
            for a in frame.distal_angle_rad {
                prop_assert!(a.is_finite() && a.abs() < 5.0, "{a}");
            }
            for s in hand.fingers() {
                prop_assert!(s.proximal_force_n.is_finite() && s.distal_force_n.is_finite());
            }
            prop_assert!(hand.tension_n().is_finite());
        }
    }

    #[test]
    fn invalid_values_are_typed_errors(
        bad in prop_oneof![Just(f64::NAN), Just(f64::INFINITY), Just(-1.0), 131.0f64..1e9],
        which in 0usize..4,
    ) {
        let mut config = UnderactuatedConfig::default();
        match which {
            0 => config.object.size_mm = bad,
            1 => config.step_ms = if bad > 0.0 && bad.is_finite() { 1e9 } else { bad },
            2 => config.object.modulus_pa = Some(if bad > 0.0 && bad.is_finite() { -bad } else { bad }),
            _ => config.object.local_width_factor[1] = if bad > 0.0 && bad.is_finite() { -bad } else { bad },
        }
        let result = Underactuated::new(&config, 1);
        prop_assert!(matches!(result, Err(SimError::Config { .. })), "{result:?}");
    }
}
