//! Softness classifier (seed 001): single-sample inference (f32, 8 readings), a whole grasp
//! (141 samples), and the wall time of one committed-recipe training run with
//! Levenberg–Marquardt and with Adam (same network, same data).

use criterion::{Criterion, criterion_group, criterion_main};
use paper_experiments::data::underactuated::{self, GraspSet};
use paper_experiments::softness_eval::{MODEL_DIR, labelled, model_file, recipe, refs};
use std::hint::black_box;
use std::path::Path;
use std::time::Duration;
use tactile_nets::softness::SoftnessNet;
use tactile_nets::softness_train::{Optimiser, train};

fn bench(c: &mut Criterion) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let grasps = underactuated::load(&root).expect("committed dataset");
    let net = SoftnessNet::load(&root.join(MODEL_DIR).join(model_file("lm", 1)))
        .expect("committed model");
    let tests = labelled(&grasps, GraspSet::TestIrregular);
    let series = tests[0].0.as_flattened().to_vec();
    let sample = series[70 * 8..71 * 8].to_vec();
    let mut group = c.benchmark_group("softness");
    group.bench_function("inference/sample", |b| {
        b.iter(|| net.sample_outputs(black_box(&sample)))
    });
    group.bench_function("inference/grasp_141_samples", |b| {
        b.iter(|| net.predict(black_box(&series)))
    });
    group.finish();

    let train_set = labelled(&grasps, GraspSet::Train);
    let train_set = refs(&train_set);
    let mut group = c.benchmark_group("softness_training");
    group
        .sample_size(10)
        .measurement_time(Duration::from_secs(60));
    for optimiser in [Optimiser::lm(), Optimiser::adam()] {
        group.bench_function(optimiser.name(), |b| {
            b.iter(|| train(black_box(&train_set), &recipe(optimiser, 1)).expect("training runs"))
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
