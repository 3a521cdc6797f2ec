//! Contact CNN: single-sample f32 inference (one 4 × 38 window) for each committed variant,
//! through the plain-array path and through dfdx's forward, and the wall time of one training
//! epoch of each variant on one depth's augmented 80 % split (6048 windows).

use criterion::{Criterion, criterion_group, criterion_main};
use paper_experiments::cnn_eval::{
    self, Case, Grouping, MODEL_DIR, NOISY_COPIES, Protocol, SEED, SNR_DB,
};
use paper_experiments::data::imu_pad;
use std::hint::black_box;
use std::path::Path;
use std::time::Duration;
use tactile_nets::contact_cnn::{ContactCnn, DfdxCnn, Variant};

fn bench(c: &mut Criterion) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let taps = imu_pad::load(&root).expect("committed dataset");
    let case = Case::Depth(1000);
    let data = cnn_eval::augment(&taps, &case.taps(&taps), NOISY_COPIES, SNR_DB, SEED);
    let x = data.windows[0];
    let mut group = c.benchmark_group("contact_cnn");
    for variant in Variant::ALL {
        let cnn = ContactCnn::load(&root.join(MODEL_DIR).join(cnn_eval::model_file(variant)))
            .expect("committed model");
        group.bench_function(format!("{}/infer", variant.name()), |b| {
            b.iter(|| cnn.predict(black_box(&x)))
        });
        let reference = DfdxCnn::of(&cnn).expect("the dfdx graph of a committed model");
        group.bench_function(format!("{}/infer_dfdx", variant.name()), |b| {
            b.iter(|| reference.logits(black_box(&x)))
        });
    }
    group.finish();
    let (train, _) = cnn_eval::split(&data, Protocol::Trials, Grouping::Samples, 0, SEED);
    let (w, r) = data.pick(&train);
    let mut group = c.benchmark_group("contact_cnn_train");
    group.sample_size(10).warm_up_time(Duration::from_millis(1));
    for variant in Variant::ALL {
        let mut config = cnn_eval::recipe(variant, SEED, String::new());
        config.epochs = 1;
        group.bench_function(format!("{}/epoch_6048", variant.name()), |b| {
            b.iter(|| ContactCnn::train(black_box(&w), &r, variant, &config))
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
