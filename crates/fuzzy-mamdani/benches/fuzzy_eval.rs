//! Evaluation cost of the 81-rule reference engine (centroid, 201 samples; MATLAB's end points
//! and fuzzylite's midpoints) and of the paper's grasp preset (center average).
#![allow(missing_docs)] // criterion's macros generate undocumented items

#[path = "../tests/common/mod.rs"]
mod common;

use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;

fn inputs() -> Vec<[f64; 2]> {
    common::bench_inputs()
}

fn reference(c: &mut Criterion) {
    let xs = inputs();
    let e64 = common::reference_201::<f64>();
    let mut s64 = e64.scratch();
    let mut k = 0;
    c.bench_function("reference_centroid201_f64", |b| {
        b.iter(|| {
            k = (k + 1) % xs.len();
            black_box(e64.evaluate(&mut s64, black_box(&xs[k])).map(|y| y[0]))
        })
    });
    // fuzzylite's semantics (midpoint integration), as pyfuzzylite's peer runs it.
    let mid = common::reference_midpoints_201::<f64>();
    let mut smid = mid.scratch();
    c.bench_function("reference_midpoints201_f64", |b| {
        b.iter(|| {
            k = (k + 1) % xs.len();
            black_box(mid.evaluate(&mut smid, black_box(&xs[k])).map(|y| y[0]))
        })
    });
    let e32 = common::reference_201::<f32>();
    let mut s32 = e32.scratch();
    let xs32: Vec<[f32; 2]> = xs.iter().map(|x| [x[0] as f32, x[1] as f32]).collect();
    c.bench_function("reference_centroid201_f32", |b| {
        b.iter(|| {
            k = (k + 1) % xs32.len();
            black_box(e32.evaluate(&mut s32, black_box(&xs32[k])).map(|y| y[0]))
        })
    });
}

fn preset(c: &mut Criterion) {
    let xs: Vec<[f32; 2]> = inputs()
        .iter()
        .map(|x| [x[0] as f32, x[1] as f32])
        .collect();
    let engine = fuzzy_mamdani::grasp_engine::<f32>();
    let mut s = engine.scratch();
    let mut k = 0;
    c.bench_function("grasp_preset_center_average_f32", |b| {
        b.iter(|| {
            k = (k + 1) % xs.len();
            black_box(engine.evaluate(&mut s, black_box(&xs[k])).map(|y| y[0]))
        })
    });
}

criterion_group!(benches, reference, preset);
criterion_main!(benches);
