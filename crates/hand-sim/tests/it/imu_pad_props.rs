//! No NaN / inf and no panic for any input: extreme depths, any grid index, zero-length taps,
//! odd time steps. Bad inputs are typed `SimError`s.

use hand_sim::SimError;
use hand_sim::imu_pad::force::ForceCounts;
use hand_sim::imu_pad::{ImuPad, ImuPadConfig, TapPosition, TapSpec, TapTiming};
use hand_sim::scene::Model;
use proptest::prelude::*;

fn finite_frames(pad: &mut ImuPad) -> bool {
    pad.drain_frames().iter().all(|f| {
        f.accel_mps2
            .iter()
            .chain(&f.gyro_rps)
            .all(|v| v.is_finite())
            && f.pressure_pa.is_none_or(f32::is_finite)
    })
}

fn depth() -> impl Strategy<Value = f64> {
    prop_oneof![
        Just(0.0),
        Just(-0.0),
        Just(f64::MIN_POSITIVE),
        Just(1e300),
        Just(-1e300),
        -5.0..5.0_f64,
        -1e6..1e6_f64,
    ]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]

    #[test]
    fn force_and_counts_are_finite_for_any_depth(d in prop_oneof![depth(), Just(f64::NAN), Just(f64::INFINITY)]) {
        let curve = ImuPadConfig::default().mechanics.curve().unwrap();
        let f = curve.force_n(d);
        prop_assert!(f.is_finite() && f >= 0.0);
        let p = ForceCounts::default().counts(f);
        prop_assert!(p.is_finite() && p >= 0.0);
    }

    #[test]
    fn any_depth_reads_finite_frames(d in depth(), col in 1_u8..=3, row in 1_u8..=24) {
        let cfg = ImuPadConfig {
            taps: vec![TapSpec { column: col, row, depth_mm: d }],
            ..ImuPadConfig::default()
        };
        let mut pad = ImuPad::new(&cfg, 1).unwrap();
        pad.step_to(3_600_000_000).unwrap();
        prop_assert!(finite_frames(&mut pad));
    }

    #[test]
    fn off_grid_positions_are_typed_errors(col in any::<u8>(), row in any::<u8>()) {
        let on_grid = (1..=3).contains(&col) && (1..=24).contains(&row);
        prop_assert_eq!(TapPosition::new(col, row).is_ok(), on_grid);
        let cfg = ImuPadConfig {
            taps: vec![TapSpec { column: col, row, depth_mm: 1.0 }],
            ..ImuPadConfig::default()
        };
        match ImuPad::new(&cfg, 2) {
            Ok(_) => prop_assert!(on_grid),
            Err(e) => prop_assert!(
                !on_grid && matches!(e, SimError::Config { .. }),
                "{:?}",
                e
            ),
        }
    }

    #[test]
    fn zero_length_and_odd_timings_never_panic(
        press in prop_oneof![Just(0.0), 0.0..0.5_f64],
        hold in prop_oneof![Just(0.0), 0.0..1.0_f64],
        release in prop_oneof![Just(0.0), 0.0..0.5_f64],
        slack in prop_oneof![Just(0.0), 0.0..1.0_f64],
        bad in prop_oneof![Just(f64::NAN), Just(-1.0), Just(f64::INFINITY)],
    ) {
        let timing = TapTiming { start_s: 0.2, tap_s: press + hold + release + slack, lead_s: 0.0, press_s: press, hold_s: hold, release_s: release };
        let cfg = ImuPadConfig {
            taps: vec![TapSpec { column: 2, row: 13, depth_mm: 1.6 }; 3],
            timing,
            ..ImuPadConfig::default()
        };
        let mut pad = ImuPad::new(&cfg, 3).unwrap();
        pad.step_to(3_000_000_000).unwrap();
        prop_assert!(finite_frames(&mut pad));
        let broken = ImuPadConfig { timing: TapTiming { press_s: bad, ..timing }, ..cfg };
        let err = ImuPad::new(&broken, 3).err();
        prop_assert!(matches!(err, Some(SimError::Config { .. })), "{:?}", err);
    }

    #[test]
    fn odd_time_steps_are_safe(steps in proptest::collection::vec(any::<u64>(), 1..6)) {
        let cfg = ImuPadConfig { max_samples_per_step: 200, buffer_frames: 64, ..ImuPadConfig::default() };
        let mut pad = ImuPad::new(&cfg, 4).unwrap();
        for t in steps {
            let before = pad.steps();
            match pad.step_to(t) {
                Ok(()) => {}
                // Too far ahead in one step: refused, nothing read.
                Err(SimError::Config { field: "max_samples_per_step", .. }) => {
                    prop_assert_eq!(pad.steps(), before);
                }
                Err(e) => prop_assert!(false, "{e}"),
            }
            // Stepping backwards or to now is a no-op.
            let now = pad.steps();
            pad.step_to(0).unwrap();
            prop_assert_eq!(pad.steps(), now);
        }
        let frames = pad.drain_frames();
        prop_assert!(frames.len() <= 64);
        prop_assert!(frames.windows(2).all(|w| w[0].t_us < w[1].t_us));
    }
}

#[test]
fn non_finite_depths_and_bad_settings_are_typed_errors() {
    for d in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        let cfg = ImuPadConfig {
            taps: vec![TapSpec {
                column: 1,
                row: 1,
                depth_mm: d,
            }],
            ..ImuPadConfig::default()
        };
        assert!(matches!(
            ImuPad::new(&cfg, 0),
            Err(SimError::Config {
                field: "taps.depth_mm",
                ..
            })
        ));
    }
    let mut cfg = ImuPadConfig {
        sample_rate_hz: 0.0,
        ..ImuPadConfig::default()
    };
    assert!(matches!(ImuPad::new(&cfg, 0), Err(SimError::Config { .. })));
    cfg.sample_rate_hz = 30.0;
    cfg.mechanics.force_points.clear();
    assert!(matches!(ImuPad::new(&cfg, 0), Err(SimError::Config { .. })));
    // ULN conversions (94.5 ms) do not fit a 33 ms frame.
    let uln = ImuPadConfig {
        baro_mode: imu_icm20789::BaroMode::UltraLowNoise,
        ..ImuPadConfig::default()
    };
    assert!(matches!(
        ImuPad::new(&uln, 0),
        Err(SimError::Config {
            field: "baro_mode",
            ..
        })
    ));
}
