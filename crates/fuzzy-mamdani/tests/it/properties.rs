//! Any finite input, however far outside the universe, gives a finite output or the declared
//! default; f32 and f64 engines agree within f32 precision; universes from 1e-300 to the largest
//! float give the unit engine's answer, scaled.

use crate::common;

use fuzzy_mamdani::{
    BuildError, Defuzzifier, Engine, EngineBuilder, EvalError, Mf, OutOfRange, Real, Resolution,
    surface,
};
use proptest::prelude::*;

/// A small engine whose rules can all stay silent (compact supports), with a declared default.
fn sparse<T: Real>(defuzz: Defuzzifier, policy: OutOfRange) -> Engine<T> {
    let tri = |a: f64, b: f64, c: f64| Mf::Triangle {
        a: T::of(a),
        b: T::of(b),
        c: T::of(c),
    };
    EngineBuilder::new("sparse")
        .out_of_range(policy)
        .input(
            "x",
            T::of(-1.0),
            T::one(),
            [("lo", tri(-1.0, -0.6, -0.2)), ("hi", tri(0.2, 0.6, 1.0))],
        )
        .defuzzifier(defuzz)
        .default_value(T::of(0.5))
        .output(
            "y",
            T::zero(),
            T::one(),
            [("a", tri(0.0, 0.2, 0.4)), ("b", tri(0.6, 0.8, 1.0))],
        )
        .rule("if x is lo then y is a")
        .rule("if x is hi then y is b")
        .build()
        .expect("builds")
}

fn defuzzifiers() -> Vec<Defuzzifier> {
    let mut all = vec![Defuzzifier::CenterAverage, Defuzzifier::WeightedAverage];
    for r in [Resolution::Samples(101), Resolution::Exact] {
        all.extend([
            Defuzzifier::Centroid(r),
            Defuzzifier::Bisector(r),
            Defuzzifier::MeanOfMaximum(r),
            Defuzzifier::SmallestOfMaximum(r),
            Defuzzifier::LargestOfMaximum(r),
        ]);
    }
    all
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 200, ..ProptestConfig::default() })]

    #[test]
    fn finite_input_gives_finite_output_or_the_default(x in prop::num::f64::NORMAL | prop::num::f64::SUBNORMAL | prop::num::f64::ZERO) {
        for d in defuzzifiers() {
            for policy in [OutOfRange::Clamp, OutOfRange::Evaluate] {
                let e = sparse::<f64>(d, policy);
                let mut s = e.scratch();
                let y = e.evaluate(&mut s, &[x]).expect("a default is declared")[0];
                prop_assert!(y.is_finite() && (0.0..=1.0).contains(&y), "{d:?} {policy:?} x={x}: {y}");
            }
            let strict = sparse::<f64>(d, OutOfRange::Error);
            let mut s = strict.scratch();
            match strict.evaluate(&mut s, &[x]) {
                Ok(y) => prop_assert!(y[0].is_finite() && (-1.0..=1.0).contains(&x)),
                Err(err) => prop_assert_eq!(err, EvalError::OutOfRange { input: 0 }),
            }
        }
    }

    #[test]
    fn reference_engine_is_finite_anywhere(e in -1e300f64..1e300, de in -1e300f64..1e300) {
        let engine = common::reference_201::<f64>();
        let mut s = engine.scratch();
        let y = engine.evaluate(&mut s, &[e, de]).expect("Gaussian ends always fire after clamping")[0];
        prop_assert!(y.is_finite() && (-1.0..=1.0).contains(&y));
    }

    #[test]
    fn f32_and_f64_agree(e in -1.5f64..1.5, de in -1.5f64..1.5) {
        let r = Resolution::Samples(201);
        for d in [Defuzzifier::Centroid(r), Defuzzifier::CenterAverage, Defuzzifier::WeightedAverage] {
            let (a, b) = (common::reference_engine::<f64>(d), common::reference_engine::<f32>(d));
            let (mut sa, mut sb) = (a.scratch(), b.scratch());
            let y64 = a.evaluate(&mut sa, &[e, de]).expect("fires")[0];
            let y32 = b.evaluate(&mut sb, &[e as f32, de as f32]).expect("fires")[0];
            // Inputs round to f32 (ulp ~6e-8) and memberships have slopes up to 4: allow 1e-5.
            prop_assert!((y64 - f64::from(y32)).abs() < 1e-5, "{d:?} ({e}, {de}): {y64} vs {y32}");
        }
    }
}

#[test]
fn non_finite_inputs_are_errors_unless_clamped() {
    let e = sparse::<f64>(
        Defuzzifier::Centroid(Resolution::Exact),
        OutOfRange::Evaluate,
    );
    let mut s = e.scratch();
    assert_eq!(
        e.evaluate(&mut s, &[f64::NAN]),
        Err(EvalError::NonFiniteInput { input: 0 })
    );
    assert_eq!(
        e.evaluate(&mut s, &[f64::INFINITY]),
        Err(EvalError::NonFiniteInput { input: 0 })
    );
    assert_eq!(
        e.evaluate(&mut s, &[0.0, 1.0]),
        Err(EvalError::InputCount {
            expected: 1,
            got: 2
        })
    );
    let clamped = sparse::<f64>(Defuzzifier::Centroid(Resolution::Exact), OutOfRange::Clamp);
    let mut s = clamped.scratch();
    assert!(clamped.evaluate(&mut s, &[f64::NEG_INFINITY]).is_ok());
}

#[test]
fn no_firing_without_default_is_an_error_not_nan() {
    let tri = |a, b, c| Mf::Triangle { a, b, c };
    let e = EngineBuilder::<f64>::new("silent")
        .input("x", 0.0, 1.0, [("mid", tri(0.4, 0.5, 0.6))])
        .output("y", 0.0, 1.0, [("t", tri(0.0, 0.5, 1.0))])
        .rule("if x is mid then y is t")
        .build()
        .expect("builds");
    let mut s = e.scratch();
    assert_eq!(
        e.evaluate(&mut s, &[0.0]),
        Err(EvalError::NoRuleFired { output: 0 })
    );
    let other = common::reference_201::<f64>();
    assert_eq!(
        other.evaluate(&mut s, &[0.0, 0.0]),
        Err(EvalError::ScratchMismatch)
    );
}

/// `lo + t (hi − lo)` without forming `hi − lo` (it overflows on the widest universes).
fn at<T: Real>(lo: T, hi: T, t: f64) -> T {
    lo * T::of(1.0 - t) + hi * T::of(t)
}

/// One engine, its terms placed at fractions of the universe `[lo, hi]` (inputs and output):
/// triangles, a Gaussian and a sigmoid in, triangles and a trapezoid out.
fn placed<T: Real>(lo: T, hi: T, d: Defuzzifier) -> Result<Engine<T>, BuildError> {
    let p = |t: f64| at(lo, hi, t);
    let width = |t: f64| at(T::zero(), hi, t) - at(T::zero(), lo, t);
    let tri = |a, b, c| Mf::Triangle {
        a: p(a),
        b: p(b),
        c: p(c),
    };
    EngineBuilder::new("placed")
        .input(
            "x",
            lo,
            hi,
            [
                ("lo", tri(0.0, 0.0, 0.6)),
                (
                    "mid",
                    Mf::Gaussian {
                        sigma: width(0.2),
                        mean: p(0.5),
                    },
                ),
                (
                    "hi",
                    Mf::Sigmoid {
                        // 12 / span, the span halved: on the widest universes it is no float.
                        a: T::of(6.0) / width(0.5),
                        c: p(0.7),
                    },
                ),
            ],
        )
        .defuzzifier(d)
        .output(
            "y",
            lo,
            hi,
            [
                ("a", tri(0.0, 0.0, 0.5)),
                ("b", tri(0.2, 0.5, 0.8)),
                (
                    "c",
                    Mf::Trapezoid {
                        a: p(0.5),
                        b: p(0.9),
                        c: p(1.0),
                        d: p(1.0),
                    },
                ),
            ],
        )
        .rule("if x is lo then y is a")
        .rule("if x is mid then y is b with 0.8")
        .rule("if x is hi then y is c")
        .build()
}

/// On `[lo, hi]` the engine answers what it answers on `[0, 1]`, carried over: `at(lo, hi, y₀)`
/// within `tol` of the span (each finite, every input inside the universe).
fn scales_like_the_unit_engine<T: Real>(
    lo: T,
    hi: T,
    u: f64,
    tol: f64,
) -> Result<(), TestCaseError> {
    let (r, m) = (Resolution::Samples(101), Resolution::Midpoints(100));
    for d in [
        Defuzzifier::Centroid(r),
        Defuzzifier::Centroid(m),
        Defuzzifier::Centroid(Resolution::Exact),
        Defuzzifier::Bisector(Resolution::Exact),
        Defuzzifier::MeanOfMaximum(Resolution::Exact),
        Defuzzifier::CenterAverage,
        Defuzzifier::WeightedAverage,
    ] {
        let unit = placed::<T>(T::zero(), T::one(), d).expect("the unit engine builds");
        let wide = placed(lo, hi, d)
            .map_err(|e| TestCaseError::fail(format!("{d:?} [{lo}, {hi}]: {e}")))?;
        let (mut su, mut sw) = (unit.scratch(), wide.scratch());
        let y0 = unit.evaluate(&mut su, &[T::of(u)]).expect("fires")[0].to_f64_lossless();
        let y = wide
            .evaluate(&mut sw, &[at(lo, hi, u)])
            .map_err(|e| TestCaseError::fail(format!("{d:?} [{lo}, {hi}] at {u}: {e}")))?[0];
        prop_assert!(
            y.is_finite() && y >= lo && y <= hi,
            "{d:?} [{lo}, {hi}] at {u}: {y}"
        );
        let want = at(lo, hi, y0);
        let half = hi.to_f64_lossless() / 2.0 - lo.to_f64_lossless() / 2.0;
        let gap = (y.to_f64_lossless() / 2.0 - want.to_f64_lossless() / 2.0).abs() / half;
        prop_assert!(
            gap <= tol,
            "{d:?} [{lo}, {hi}] at {u}: {y} vs {want} ({gap:e} of the span)"
        );
    }
    Ok(())
}

/// A universe of magnitude `m`: `[0, m]`, `[−m, m]`, `[−m, 0]` or `[m/4, m]`.
fn universe(m: f64, kind: u8) -> (f64, f64) {
    match kind % 4 {
        0 => (0.0, m),
        1 => (-m, m),
        2 => (-m, 0.0),
        _ => (m / 4.0, m),
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    #[test]
    fn any_f64_universe_scales(exp in -300.0f64..308.25, kind in 0u8..4, u in 0.0f64..1.0) {
        let m = 10f64.powf(exp).min(f64::MAX);
        let (lo, hi) = universe(m, kind);
        // Relative rounding of the placed break points and of the answer, a few ulps of 1.
        scales_like_the_unit_engine::<f64>(lo, hi, u, 1e-9)?;
    }

    #[test]
    fn any_f32_universe_scales(exp in -30.0f64..38.53, kind in 0u8..4, u in 0.0f64..1.0) {
        let m = (10f64.powf(exp) as f32).min(f32::MAX);
        let (lo, hi) = universe(f64::from(m), kind);
        scales_like_the_unit_engine::<f32>(lo as f32, hi as f32, u, 1e-3)?;
    }
}

/// Probes at the extremes of f64, each answered (finite, in the universe) or refused with a typed
/// error.
#[test]
fn the_probes_at_the_extremes_are_answered_or_refused() {
    let sampled = Defuzzifier::Centroid(Resolution::Samples(201));
    for (lo, hi) in [(-1e308, 1e308), (0.0, 5e307), (-f64::MAX, f64::MAX)] {
        for d in [
            sampled,
            Defuzzifier::Bisector(Resolution::Samples(201)),
            Defuzzifier::MeanOfMaximum(Resolution::Samples(201)),
            Defuzzifier::Centroid(Resolution::Exact),
        ] {
            let e = placed(lo, hi, d).expect("builds");
            let mut s = e.scratch();
            let y = e.evaluate(&mut s, &[at(lo, hi, 0.3)]).expect("answers")[0];
            assert!(
                y.is_finite() && y >= lo && y <= hi,
                "{d:?} [{lo}, {hi}]: {y}"
            );
        }
    }
    for (lo, hi) in [(-f32::MAX, f32::MAX), (0.0, 1e38), (0.0, 1e20)] {
        let e = placed(lo, hi, Defuzzifier::Centroid(Resolution::Exact)).expect("builds");
        let mut s = e.scratch();
        let y = e.evaluate(&mut s, &[at(lo, hi, 0.3)]).expect("answers")[0];
        assert!(y.is_finite() && y >= lo && y <= hi, "f32 [{lo}, {hi}]: {y}");
    }
    // The moment of [0, 1e155] grows as x²: exact in the universe's frame.
    let e = placed(0.0f64, 1e155, Defuzzifier::Centroid(Resolution::Exact)).expect("builds");
    let mut s = e.scratch();
    assert!(e.evaluate(&mut s, &[3e154]).expect("answers")[0].is_finite());

    // Memberships whose textbook formula is ∞/∞ or 0·∞.
    let (min, max) = (f64::MIN, f64::MAX);
    let cases = [
        (
            Mf::Triangle {
                a: min,
                b: max,
                c: max,
            },
            1e308,
            0.5 + 0.5 * 1e308 / max,
        ),
        (
            Mf::Trapezoid {
                a: min,
                b: max,
                c: max,
                d: max,
            },
            0.0,
            0.5,
        ),
        (Mf::Sigmoid { a: 0.0, c: min }, max, 0.5),
        (
            Mf::SigmoidDifference {
                a1: 0.0,
                c1: min,
                a2: 1.0,
                c2: 0.0,
            },
            max,
            0.5,
        ),
        (
            Mf::Gaussian {
                sigma: max,
                mean: min,
            },
            max,
            (-2.0f64).exp(),
        ),
    ];
    for (mf, x, want) in cases {
        assert_eq!(mf.validate(), Ok(()));
        let m = mf.membership(x);
        assert!((m - want).abs() < 1e-12, "{mf:?} at {x}: {m}, not {want}");
    }

    // Center average of two full rules into a term centred at the largest float.
    let top = Mf::Triangle {
        a: 0.0,
        b: max,
        c: max,
    };
    assert_eq!(
        common::single_term(top, 0.0, max, Defuzzifier::CenterAverage, 2),
        Ok(max)
    );
}

/// Engines that could never answer are refused when built.
#[test]
fn engines_that_cannot_answer_are_build_errors() {
    let tri = |a, b, c| Mf::Triangle { a, b, c };
    let base = || {
        EngineBuilder::<f64>::new("degenerate").input("x", 0.0, 1.0, [("t", tri(0.0, 0.5, 1.0))])
    };
    // Every rule of weight 0.
    let zero = base()
        .output("y", 0.0, 1.0, [("t", tri(0.0, 0.5, 1.0))])
        .rule("if x is t then y is t with 0")
        .build();
    assert_eq!(
        zero.unwrap_err(),
        BuildError::NeverAnswers { output: "y".into() }
    );
    // A zero-width output term on the exact path.
    let spike = base()
        .defuzzifier(Defuzzifier::Centroid(Resolution::Exact))
        .output("y", 0.0, 1.0, [("t", tri(0.5, 0.5, 0.5))])
        .rule("if x is t then y is t")
        .build();
    assert!(
        matches!(spike, Err(BuildError::Defuzzifier { .. })),
        "{spike:?}"
    );
    // A Gaussian narrower than the samples' spacing, between two samples.
    let narrow = |mean: f64| {
        base()
            .defuzzifier(Defuzzifier::Centroid(Resolution::Samples(101)))
            .output(
                "y",
                0.0,
                1.0,
                [(
                    "g",
                    Mf::Gaussian {
                        sigma: 1e-300,
                        mean,
                    },
                )],
            )
            .rule("if x is t then y is g")
            .build()
    };
    assert!(matches!(narrow(0.505), Err(BuildError::Defuzzifier { .. })));
    // On a sample it is seen, and the answer is that sample.
    let on = narrow(0.5).expect("a sample sees it");
    let mut s = on.scratch();
    assert_eq!(on.evaluate(&mut s, &[0.5]), Ok(&[0.5][..]));
    // A surface larger than any memory, refused instead of overflowing.
    let e = common::reference_201::<f64>();
    for steps in [usize::MAX, 1 << 31] {
        assert!(matches!(
            surface(&e, steps),
            Err(EvalError::TooManySteps { .. })
        ));
    }
}
