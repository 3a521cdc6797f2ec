//! Any finite input, however far outside the universe, gives a finite output or the declared
//! default; f32 and f64 engines agree within f32 precision.

mod common;

use fuzzy_mamdani::{
    Defuzzifier, Engine, EngineBuilder, EvalError, Mf, OutOfRange, Real, Resolution,
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
