//! Evaluation allocates nothing once the engine and its scratch exist, and the grasp preset's
//! controller allocates nothing at all: dhat's counting global allocator proves it for every
//! defuzzifier path, chained engines and the controller.

mod common;

use fuzzy_mamdani::{Defuzzifier, EngineBuilder, Mf, Resolution, SNorm};

// dhat's allocator counts every heap block; its testing mode makes the counts readable.
#[global_allocator]
static ALLOC: dhat::Alloc = dhat::Alloc;

fn no_evaluation_allocates() {
    let r = Resolution::Samples(201);
    let mut engines = vec![
        common::reference_201::<f64>(),
        common::reference_engine::<f64>(Defuzzifier::CenterAverage),
        common::reference_engine::<f64>(Defuzzifier::WeightedAverage),
        common::reference_engine::<f64>(Defuzzifier::Bisector(r)),
        common::reference_engine::<f64>(Defuzzifier::MeanOfMaximum(r)),
    ];
    // The exact path, with both aggregations that support it.
    for agg in [SNorm::Maximum, SNorm::UnboundedSum] {
        for d in [
            Defuzzifier::Centroid(Resolution::Exact),
            Defuzzifier::Bisector(Resolution::Exact),
        ] {
            let tri = |b: f64| Mf::Triangle {
                a: b - 0.5,
                b,
                c: b + 0.5,
            };
            engines.push(
                EngineBuilder::new("exact")
                    .input(
                        "x",
                        0.0,
                        1.0,
                        [
                            (
                                "lo",
                                Mf::Trapezoid {
                                    a: 0.0,
                                    b: 0.0,
                                    c: 0.2,
                                    d: 0.8,
                                },
                            ),
                            ("hi", tri(1.0)),
                        ],
                    )
                    .aggregation(agg)
                    .defuzzifier(d)
                    .output("y", 0.0, 1.0, [("a", tri(0.25)), ("b", tri(0.75))])
                    .rule("if x is lo then y is a")
                    .rule("if x is hi or x is not lo then y is b")
                    .build()
                    .expect("builds"),
            );
        }
    }
    // fuzzylite's semantics: hedges, activation methods, midpoints, every term class.
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/fuzzy");
    for name in [
        "fl_hedges",
        "fl_terms",
        "fl_none_ops",
        "fl_act_highest",
        "fl_act_proportional",
        "fl_chained",
        "fl_chained_blocks",
    ] {
        let fll = std::fs::read_to_string(dir.join(format!("{name}.fll"))).expect("fixture");
        engines.push(fuzzy_mamdani::from_fll(&fll).expect("imports"));
    }
    let _profiler = dhat::Profiler::builder().testing().build();
    let preset = fuzzy_mamdani::grasp_engine::<f64>();
    for engine in engines.iter().chain([&preset]) {
        let mut scratch = engine.scratch();
        let inputs: Vec<Vec<f64>> = (0..50)
            .map(|k| vec![-1.2 + 0.05 * k as f64; engine.inputs().len()])
            .collect();
        let before = dhat::HeapStats::get().total_blocks;
        let mut sum = 0.0;
        for x in &inputs {
            // Inputs reach past the universe: the default clamp policy still answers; fuzzylite's
            // engines evaluate them where they are, where no rule may fire.
            match engine.evaluate(&mut scratch, x) {
                Ok(y) => sum += y[0],
                Err(e) => assert!(
                    engine.name().starts_with("fl_")
                        && matches!(e, fuzzy_mamdani::EvalError::NoRuleFired { .. }),
                    "{}: {e}",
                    engine.name()
                ),
            }
        }
        let after = dhat::HeapStats::get().total_blocks;
        assert!(sum.is_finite());
        assert_eq!(
            after - before,
            0,
            "{}: {} allocations in 50 evaluations",
            engine.name(),
            after - before
        );
    }
}

/// The grasp preset's controller is built and evaluated without a heap (a fingertip's firmware
/// has no allocator).
fn the_grasp_controller_never_allocates() {
    use hand_traits::{GraspObservation, GraspPolicy};
    let _profiler = dhat::Profiler::builder().testing().build();
    let before = dhat::HeapStats::get().total_blocks;
    let mut controller = fuzzy_mamdani::grasp_controller().with_torque_band(50, 1023);
    let mut sum = 0.0;
    for k in 0..50 {
        let obs = GraspObservation {
            pressure_error_pa: -3_000.0 + 120.0 * k as f32,
            pressure_rate_pa_per_s: 12_000.0 - 500.0 * k as f32,
        };
        sum += controller.effort(&obs).expect("answers").fraction();
    }
    let after = dhat::HeapStats::get().total_blocks;
    assert!(sum > 0.0);
    assert_eq!(after - before, 0, "{} allocations", after - before);
}

// No libtest harness (`harness = false`): its main thread allocates (the running-test table, the
// timeout queue) while a test thread runs, and dhat counts every thread's blocks.
fn main() {
    no_evaluation_allocates();
    println!("no_evaluation_allocates: ok");
    the_grasp_controller_never_allocates();
    println!("the_grasp_controller_never_allocates: ok");
}
