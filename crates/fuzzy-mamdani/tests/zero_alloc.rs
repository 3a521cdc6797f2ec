//! Evaluation allocates nothing once the engine and its scratch exist: a counting global
//! allocator proves it for every defuzzifier path.
#![allow(unsafe_code)] // a GlobalAlloc impl is unsafe by definition; it only forwards to System

mod common;

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

use fuzzy_mamdani::{Defuzzifier, EngineBuilder, Mf, Resolution, SNorm};

struct Counting;
static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);

// SAFETY: forwards to the system allocator unchanged; only counts calls.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::SeqCst);
        // SAFETY: same contract as the caller's.
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: same contract as the caller's.
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::SeqCst);
        // SAFETY: same contract as the caller's.
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

#[test]
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
    let preset = fuzzy_mamdani::grasp_engine::<f64>();
    for engine in engines.iter().chain([&preset]) {
        let mut scratch = engine.scratch();
        let inputs: Vec<Vec<f64>> = (0..50)
            .map(|k| vec![-1.2 + 0.05 * k as f64; engine.inputs().len()])
            .collect();
        let before = ALLOCATIONS.load(Ordering::SeqCst);
        let mut sum = 0.0;
        for x in &inputs {
            if let Ok(y) = engine.evaluate(&mut scratch, x) {
                sum += y[0];
            }
        }
        let after = ALLOCATIONS.load(Ordering::SeqCst);
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
