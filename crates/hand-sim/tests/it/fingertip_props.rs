//! No NaN or infinity anywhere in the fingertip for extreme forces, any contact, any times.

use hand_sim::fingertip::{CellSet, ContactPatch, FingertipPhysics, LawParams};
use proptest::prelude::*;

proptest! {
    #[test]
    fn steady_rise_is_finite_and_non_negative(mask in 0u32..(1 << 24), force in prop_oneof![Just(f64::INFINITY), Just(0.0), Just(f64::MAX), 0.0..1e7]) {
        let cells = hand_sim::fingertip::Cell::all().filter(|c| mask & (1 << c.index()) != 0).fold(CellSet::EMPTY, CellSet::with);
        let rise = LawParams::CALIBRATED.steady_rise_hpa(&ContactPatch { cells, force_n: force, offset_mm: [0.0; 2] });
        for r in rise {
            prop_assert!(r.is_finite() && r >= 0.0, "{:?}", rise);
        }
    }

    #[test]
    fn pressures_stay_finite_over_any_contact_timeline(
        steps in proptest::collection::vec((0u64..5_000_000_000, 0u32..(1 << 24), 0.0f64..1e6), 0..40),
        probes in proptest::collection::vec(0u64..u64::MAX / 2, 1..20),
    ) {
        let mut physics = FingertipPhysics::new(LawParams::CALIBRATED, [1010.0; 3], 0.5).unwrap();
        let mut t = 0;
        for (dt, mask, force) in steps {
            t += dt;
            let cells = hand_sim::fingertip::Cell::all().filter(|c| mask & (1 << c.index()) != 0).fold(CellSet::EMPTY, CellSet::with);
            physics.set_contact(t, ContactPatch { cells, force_n: force, offset_mm: [0.0; 2] }).unwrap();
        }
        let mut probes = probes;
        probes.sort_unstable();
        for p in probes {
            for k in 0..3 {
                let hpa = physics.pressure_hpa(k, p);
                prop_assert!(hpa.is_finite(), "{}", hpa);
            }
        }
    }

    #[test]
    fn bad_forces_and_backward_times_are_rejected(force in prop_oneof![Just(f64::NAN), -1e9..-1e-9]) {
        let mut physics = FingertipPhysics::new(LawParams::CALIBRATED, [1010.0; 3], 0.0).unwrap();
        let bad = ContactPatch { cells: CellSet::EMPTY, force_n: force, offset_mm: [0.0; 2] };
        prop_assert!(physics.set_contact(0, bad).is_err());
        physics.set_contact(10, ContactPatch::NONE).unwrap();
        prop_assert!(physics.set_contact(5, ContactPatch::NONE).is_err());
    }
}
