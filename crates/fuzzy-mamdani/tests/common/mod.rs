//! Engines shared by the integration tests and the benchmark.
#![allow(dead_code)] // each target that includes it uses a subset

use fuzzy_mamdani::{Defuzzifier, Engine, EngineBuilder, Mf, Real, Resolution};

const NAMES: [&str; 9] = ["NH", "NB", "NM", "NS", "ZO", "PS", "PM", "PB", "PH"];

/// The benchmark's reference engine: e, de on [-1, 1], 9 terms centred at −1, −0.75 … 1
/// (NH / PH Gaussian σ = 0.1667, the rest triangles of half-width 0.25), output on [-1, 1] with
/// 9 Gaussians σ = 0.125, rules `e is T_i and de is T_j → tau is T_clamp(i+j−4)`, min / max / min.
pub(crate) fn reference_engine<T: Real>(defuzz: Defuzzifier) -> Engine<T> {
    let c = |i: usize| T::of(-1.0 + 0.25 * i as f64);
    let input_terms = || {
        (0..9).map(move |i| {
            let mf = if i == 0 || i == 8 {
                Mf::Gaussian {
                    sigma: T::of(0.1667),
                    mean: c(i),
                }
            } else {
                Mf::Triangle {
                    a: c(i) - T::of(0.25),
                    b: c(i),
                    c: c(i) + T::of(0.25),
                }
            };
            (NAMES[i], mf)
        })
    };
    let mut b = EngineBuilder::new("reference")
        .input("e", T::of(-1.0), T::one(), input_terms())
        .input("de", T::of(-1.0), T::one(), input_terms())
        .defuzzifier(defuzz)
        .output(
            "tau",
            T::of(-1.0),
            T::one(),
            (0..9).map(|i| {
                (
                    NAMES[i],
                    Mf::Gaussian {
                        sigma: T::of(0.125),
                        mean: c(i),
                    },
                )
            }),
        );
    for (i, ei) in NAMES.iter().enumerate() {
        for (j, dej) in NAMES.iter().enumerate() {
            let k = (i + j).saturating_sub(4).min(8);
            b = b.rule(format!(
                "if e is {ei} and de is {dej} then tau is {}",
                NAMES[k]
            ));
        }
    }
    b.build().expect("the reference engine builds")
}

/// The benchmarks' inputs: a deterministic sweep over the universes, including the ends and a
/// little beyond (fuzzy-mamdani's criterion bench and the workspace's instruction counts).
pub(crate) fn bench_inputs() -> Vec<[f64; 2]> {
    (0..64)
        .map(|k| {
            [
                -1.05 + 2.1 * (k as f64 * 0.618_034).fract(),
                -1.05 + 2.1 * (k as f64 * 0.414_214).fract(),
            ]
        })
        .collect()
}

/// The reference engine with its benchmark defuzzifier: centroid over 201 samples.
pub(crate) fn reference_201<T: Real>() -> Engine<T> {
    reference_engine(Defuzzifier::Centroid(Resolution::Samples(201)))
}

/// The reference engine under fuzzylite's integration: centroid over 201 midpoints.
pub(crate) fn reference_midpoints_201<T: Real>() -> Engine<T> {
    reference_engine(Defuzzifier::Centroid(Resolution::Midpoints(201)))
}

/// The crisp value of one output term `term` over `[min, max]` when `copies` identical rules
/// fire it fully (an input term that holds everywhere).
pub(crate) fn single_term(
    term: Mf<f64>,
    min: f64,
    max: f64,
    defuzz: Defuzzifier,
    copies: usize,
) -> Result<f64, fuzzy_mamdani::EvalError> {
    let all = Mf::Trapezoid {
        a: 0.0,
        b: 0.0,
        c: 1.0,
        d: 1.0,
    };
    let mut b = EngineBuilder::new("one")
        .input("x", 0.0, 1.0, [("all", all)])
        .defuzzifier(defuzz)
        .output("y", min, max, [("t", term)]);
    for _ in 0..copies {
        b = b.rule("if x is all then y is t");
    }
    let engine = b.build().expect("builds");
    let mut s = engine.scratch();
    engine.evaluate(&mut s, &[0.5]).map(|y| y[0])
}
