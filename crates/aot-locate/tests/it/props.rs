//! proptest: finite scores for any finite input, sensor-order invariance, no panics.

use aot_locate::{
    AotLocator, AreaGrid, ArrivalDetector, ArrivalEvent, DECODE_TOLERANCE, DetectorConfig,
    Geometry, Ranging, Scorer, eq3,
};
use hand_traits::ContactLocator;
use proptest::prelude::*;

/// The test pad: 18 × 12 mm (3 mm cells).
const PAD: AreaGrid = AreaGrid {
    width_mm: 18.0,
    height_mm: 12.0,
};

/// An eq. 3 locator on [`PAD`] with sensors in an inverted triangle.
fn locator() -> AotLocator {
    AotLocator::new(Geometry::new([[4.5, 1.5], [0.0, -4.5], [-4.5, 1.5]], PAD).unwrap())
}

fn finite() -> impl Strategy<Value = f32> {
    prop_oneof![
        -1e6f32..1e6f32,
        Just(0.0f32),
        Just(f32::MAX),
        Just(f32::MIN),
        Just(f32::MIN_POSITIVE),
        any::<f32>().prop_filter("finite", |v| v.is_finite()),
    ]
}

fn time() -> impl Strategy<Value = Option<u32>> {
    prop_oneof![
        Just(None),
        Just(Some(0)),
        Just(Some(u32::MAX)),
        (0u32..200_000).prop_map(Some)
    ]
}

fn event() -> impl Strategy<Value = ArrivalEvent> {
    (
        prop::array::uniform3(finite()),
        prop::array::uniform3(time()),
    )
        .prop_map(|(pressure_pa, arrival_us)| ArrivalEvent {
            pressure_pa,
            arrival_us,
        })
}

fn geometry() -> impl Strategy<Value = Geometry> {
    prop::array::uniform3(prop::array::uniform2(-20f32..20f32))
        .prop_filter_map("a sensor on an area centre", |s| Geometry::new(s, PAD).ok())
}

/// Any valid ranging model: delays, slopes and lags across and beyond the fitted ones.
fn ranging() -> impl Strategy<Value = Ranging> {
    (
        prop_oneof![
            -1e6f32..1e6f32,
            Just(0.0f32),
            Just(f32::MIN),
            Just(f32::MAX)
        ],
        prop_oneof![1e-3f32..1e6f32, Just(f32::MIN_POSITIVE), Just(f32::MAX)],
        prop_oneof![-1e6f32..1e6f32, Just(0.0f32), Just(f32::MAX)],
        prop_oneof![0f32..1e4f32, Just(0.0f32), Just(f32::MAX)],
    )
        .prop_map(|(a, b, c, theta)| Ranging::new(a, b, c, theta).unwrap())
}

const PERMUTATIONS: [[usize; 3]; 6] = [
    [0, 1, 2],
    [0, 2, 1],
    [1, 0, 2],
    [1, 2, 0],
    [2, 0, 1],
    [2, 1, 0],
];

proptest! {
    #[test]
    fn finite_input_gives_finite_scores(g in geometry(), e in event()) {
        match eq3(&g, &e) {
            Ok(s) => {
                prop_assert!(s.values().iter().all(|v| v.is_finite()));
                let c = s.confidence();
                prop_assert!((0.0..=1.0).contains(&c));
                prop_assert!(s.argmax() < 9);
            }
            Err(err) => prop_assert_eq!(err, aot_locate::AotError::NoArrival),
        }
        prop_assert_eq!(eq3(&g, &e).is_err(), e.arrival_us.iter().all(Option::is_none));
    }

    #[test]
    fn sensor_order_does_not_matter(g in geometry(), e in event(), p in 0usize..6) {
        let order = PERMUTATIONS[p];
        let pg = g.permuted(order).unwrap();
        let pe = ArrivalEvent {
            pressure_pa: order.map(|i| e.pressure_pa[i]),
            arrival_us: order.map(|i| e.arrival_us[i]),
        };
        prop_assert_eq!(eq3(&g, &e), eq3(&pg, &pe));
        prop_assert_eq!(
            AotLocator::new(g).locate(&e).map(|c| (c.region, c.confidence.to_bits())),
            AotLocator::new(pg).locate(&pe).map(|c| (c.region, c.confidence.to_bits()))
        );
    }

    #[test]
    fn ranging_scores_are_finite_for_finite_input(g in geometry(), m in ranging(), e in event()) {
        match m.scores(&g, &e) {
            Ok(s) => {
                prop_assert!(s.values().iter().all(|v| v.is_finite()), "{:?}", s.values());
                prop_assert!((0.0..=1.0).contains(&s.confidence()));
            }
            Err(err) => prop_assert_eq!(err, aot_locate::AotError::NoArrival),
        }
        prop_assert_eq!(m.scores(&g, &e).is_err(), e.arrival_us.iter().all(Option::is_none));
    }

    #[test]
    fn ranging_ignores_sensor_order(
        g in geometry(), m in ranging(), e in event(), p in 0usize..6,
    ) {
        let order = PERMUTATIONS[p];
        let pg = g.permuted(order).unwrap();
        let pe = ArrivalEvent {
            pressure_pa: order.map(|i| e.pressure_pa[i]),
            arrival_us: order.map(|i| e.arrival_us[i]),
        };
        prop_assert_eq!(m.scores(&g, &e), m.scores(&pg, &pe));
        let locate = |g, e: &ArrivalEvent| {
            AotLocator::with_scorer(g, Scorer::Ranging(m))
                .locate(e)
                .map(|c| (c.region, c.confidence.to_bits()))
        };
        prop_assert_eq!(locate(g, &e), locate(pg, &pe));
    }

    #[test]
    fn nothing_panics(
        p in prop::array::uniform3(any::<f32>()),
        t in prop::array::uniform3(any::<Option<u32>>()),
        frames in prop::collection::vec((any::<i64>(), prop::array::uniform3(any::<f32>())), 0..40),
        threshold in any::<f32>(), alpha in any::<f32>(), debounce in any::<u8>(),
        onset in any::<i64>(), label in any::<f32>(),
        sensors in prop::array::uniform3(prop::array::uniform2(any::<f32>())),
    ) {
        let e = ArrivalEvent { pressure_pa: p, arrival_us: t };
        let sane = |r: Result<hand_traits::Contact, aot_locate::AotError>| match r {
            Ok(c) => c.region < 9 && c.regions == 9 && (0.0..=1.0).contains(&c.confidence),
            Err(_) => true,
        };
        let r = locator().locate(&e);
        prop_assert_eq!(r.is_ok(), p.iter().all(|v| v.is_finite()) && t.iter().any(Option::is_some));
        prop_assert!(sane(r));
        let mut d = ArrivalDetector::new(DetectorConfig { threshold_pa: threshold, baseline_alpha: alpha, debounce });
        for (ts, f) in frames {
            d.push(ts, f);
        }
        let ev = d.event(onset, p);
        prop_assert!(sane(locator().locate(&ev)));
        if let Ok(c) = crate::labels::decode(label) {
            for set in c.as_slice() {
                prop_assert!((set.average_area().value() - label).abs() < DECODE_TOLERANCE);
            }
        }
        if let Ok(g) = Geometry::new(sensors, PAD) {
            if let Ok(s) = eq3(&g, &e) {
                prop_assert!(s.values().iter().all(|v| v.is_finite()));
            }
        }
    }
}
