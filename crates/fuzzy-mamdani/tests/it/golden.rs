//! Golden values published by MATLAB and scikit-fuzzy.

use crate::common;

use fuzzy_mamdani::{Defuzzifier, Engine, EngineBuilder, Mf, Resolution};

/// MATLAB's `tipper.fis` (Fuzzy Logic Toolbox example): service Gaussians σ = 1.5 at 0, 5, 10;
/// food trapezoids [0 0 1 3] and [7 9 10 10]; tip triangles [0 5 10], [10 15 20], [20 25 30].
fn tipper(defuzz: Defuzzifier) -> Engine<f64> {
    EngineBuilder::new("tipper")
        .input(
            "service",
            0.0,
            10.0,
            [
                (
                    "poor",
                    Mf::Gaussian {
                        sigma: 1.5,
                        mean: 0.0,
                    },
                ),
                (
                    "good",
                    Mf::Gaussian {
                        sigma: 1.5,
                        mean: 5.0,
                    },
                ),
                (
                    "excellent",
                    Mf::Gaussian {
                        sigma: 1.5,
                        mean: 10.0,
                    },
                ),
            ],
        )
        .input(
            "food",
            0.0,
            10.0,
            [
                (
                    "rancid",
                    Mf::Trapezoid {
                        a: 0.0,
                        b: 0.0,
                        c: 1.0,
                        d: 3.0,
                    },
                ),
                (
                    "delicious",
                    Mf::Trapezoid {
                        a: 7.0,
                        b: 9.0,
                        c: 10.0,
                        d: 10.0,
                    },
                ),
            ],
        )
        .defuzzifier(defuzz)
        .output(
            "tip",
            0.0,
            30.0,
            [
                (
                    "cheap",
                    Mf::Triangle {
                        a: 0.0,
                        b: 5.0,
                        c: 10.0,
                    },
                ),
                (
                    "average",
                    Mf::Triangle {
                        a: 10.0,
                        b: 15.0,
                        c: 20.0,
                    },
                ),
                (
                    "generous",
                    Mf::Triangle {
                        a: 20.0,
                        b: 25.0,
                        c: 30.0,
                    },
                ),
            ],
        )
        .rule("if service is poor or food is rancid then tip is cheap")
        .rule("if service is good then tip is average")
        .rule("if service is excellent or food is delicious then tip is generous")
        .build()
        .expect("tipper builds")
}

/// MathWorks, `evalfis` documentation page, "Evaluate Fuzzy Inference System" example:
/// `evalfis(fis, [2 1; 4 5; 7 8])` with the default 101 defuzzification samples gives
/// 7.0169, 14.4585, 20.3414 (https://www.mathworks.com/help/fuzzy/evalfis.html).
#[test]
fn matlab_tipper_evalfis_at_101_samples() {
    let engine = tipper(Defuzzifier::Centroid(Resolution::Samples(101)));
    let mut s = engine.scratch();
    for (input, want) in [
        ([2.0, 1.0], 7.0169),
        ([4.0, 5.0], 14.4585),
        ([7.0, 8.0], 20.3414),
    ] {
        let got = engine.evaluate(&mut s, &input).expect("fires")[0];
        assert!(
            (got - want).abs() < 5e-5,
            "{input:?}: {got} vs MATLAB {want}"
        );
    }
}

/// The exact centroid is what MATLAB's sampled one converges to: within the 101-point grid error.
#[test]
fn exact_tipper_is_close_to_the_sampled_one() {
    let (exact, sampled) = (
        tipper(Defuzzifier::Centroid(Resolution::Exact)),
        tipper(Defuzzifier::Centroid(Resolution::Samples(100_001))),
    );
    let (mut a, mut b) = (exact.scratch(), sampled.scratch());
    for input in [[2.0, 1.0], [4.0, 5.0], [7.0, 8.0], [0.0, 10.0]] {
        let x = exact.evaluate(&mut a, &input).expect("fires")[0];
        let y = sampled.evaluate(&mut b, &input).expect("fires")[0];
        assert!(
            (x - y).abs() < 1e-4,
            "{input:?}: exact {x} vs 100001 samples {y}"
        );
    }
}

/// scikit-fuzzy `skfuzzy/defuzzify/tests/test_defuzz.py`: the bisector of `trimf` [0, 5, 5] over
/// 0..5 is 3.53553390593274 (= 5/√2).
#[test]
fn skfuzzy_bisector_of_a_right_triangle() {
    let b = common::single_term(
        Mf::Triangle {
            a: 0.0,
            b: 5.0,
            c: 5.0,
        },
        0.0,
        5.0,
        Defuzzifier::Bisector(Resolution::Exact),
        1,
    )
    .expect("fires");
    assert!((b - 3.535_533_905_932_74).abs() < 1e-12, "{b}");
}

/// scikit-fuzzy `test_defuzz.py`: `trapmf` [-1, 3, 7, 8] over −10..10 gives SOM 3, MOM 5, LOM 7.
#[test]
fn skfuzzy_maxima_of_a_trapezoid() {
    let t = Mf::Trapezoid {
        a: -1.0,
        b: 3.0,
        c: 7.0,
        d: 8.0,
    };
    for res in [Resolution::Exact, Resolution::Samples(201)] {
        let som = common::single_term(
            t.clone(),
            -10.0,
            10.0,
            Defuzzifier::SmallestOfMaximum(res),
            1,
        )
        .expect("fires");
        let mom = common::single_term(t.clone(), -10.0, 10.0, Defuzzifier::MeanOfMaximum(res), 1)
            .expect("fires");
        let lom = common::single_term(
            t.clone(),
            -10.0,
            10.0,
            Defuzzifier::LargestOfMaximum(res),
            1,
        )
        .expect("fires");
        assert!(
            (som - 3.0).abs() < 1e-12 && (mom - 5.0).abs() < 1e-12 && (lom - 7.0).abs() < 1e-12,
            "{res:?}: {som} {mom} {lom}"
        );
    }
}

/// scikit-fuzzy's "tipping problem" control example (docs, `plot_tipping_problem_newapi`):
/// quality 6.5, service 9.8 gives 19.8578 on its 0..25 integer tip universe (0.5.0 itself prints
/// 19.8476); the exact centroid must agree within 1 %.
#[test]
fn skfuzzy_tipping_problem() {
    let tri = |a, b, c| Mf::Triangle { a, b, c };
    let automf = || {
        [
            ("poor", tri(0.0, 0.0, 5.0)),
            ("average", tri(0.0, 5.0, 10.0)),
            ("good", tri(5.0, 10.0, 10.0)),
        ]
    };
    let engine = EngineBuilder::new("tipping")
        .input("quality", 0.0, 10.0, automf())
        .input("service", 0.0, 10.0, automf())
        .defuzzifier(Defuzzifier::Centroid(Resolution::Exact))
        .output(
            "tip",
            0.0,
            25.0,
            [
                ("low", tri(0.0, 0.0, 13.0)),
                ("medium", tri(0.0, 13.0, 25.0)),
                ("high", tri(13.0, 25.0, 25.0)),
            ],
        )
        .rule("if quality is poor or service is poor then tip is low")
        .rule("if service is average then tip is medium")
        .rule("if service is good or quality is good then tip is high")
        .build()
        .expect("builds");
    let mut s = engine.scratch();
    let tip: f64 = engine.evaluate(&mut s, &[6.5, 9.8]).expect("fires")[0];
    assert!((tip - 19.8578).abs() < 0.198_578, "{tip}");
}
