//! AoT per localisation: eq. 3, or the ranging scorer, over the nine areas, argmax and
//! confidence, through the `ContactLocator` trait (target: under 100 ns).

use aot_locate::{AotLocator, AreaGrid, ArrivalEvent, Geometry, Ranging, Scorer};
use criterion::{Criterion, criterion_group, criterion_main};
use hand_traits::ContactLocator;
use std::hint::black_box;

fn locate(c: &mut Criterion) {
    // An 18 × 12 mm pad with its sensors in an inverted triangle.
    let pad = AreaGrid {
        width_mm: 18.0,
        height_mm: 12.0,
    };
    let geometry = Geometry::new([[4.5, 1.5], [0.0, -4.5], [-4.5, 1.5]], pad).unwrap();
    let mut locator = AotLocator::new(geometry);
    // A press near sensor 1 at 7 kgf as the simulator gives it: held rises (Pa) and arrival
    // times from onset (µs); sensor 2 never arrived.
    let event = ArrivalEvent {
        pressure_pa: [4_200.0, 0.0, 1_900.0],
        arrival_us: [Some(6_060), None, Some(30_300)],
    };
    c.bench_function("aot_locate", |b| {
        b.iter(|| locator.locate(black_box(&event)))
    });
    let all = ArrivalEvent {
        pressure_pa: [4_200.0, 800.0, 1_900.0],
        arrival_us: [Some(6_060), Some(18_180), Some(30_300)],
    };
    c.bench_function("aot_locate_three_arrivals", |b| {
        b.iter(|| locator.locate(black_box(&all)))
    });
    // The ranging scorer with constants of the size fitted at OSR 256 (docs/contact-location.md).
    let model = Ranging::new(3_000.0, 2_500.0, 25_000.0, 30.0).unwrap();
    let mut ranging = AotLocator::with_scorer(geometry, Scorer::Ranging(model));
    c.bench_function("aot_ranging_three_arrivals", |b| {
        b.iter(|| ranging.locate(black_box(&all)))
    });
}

criterion_group!(benches, locate);
criterion_main!(benches);
