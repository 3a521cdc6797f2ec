//! Contact-area MLP inference per sample (f32, one tap's 9 features), for both heads, loading
//! the committed OSR 4096 models.

use criterion::{Criterion, criterion_group, criterion_main};
use paper_experiments::contact_eval::{MODEL_DIR, model_file, split};
use paper_experiments::data::fingertip;
use std::hint::black_box;
use std::path::Path;
use tactile_nets::contact_mlp::{ContactMlp, Head, features};

fn bench(c: &mut Criterion) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let records = fingertip::load(&root).expect("committed dataset").records();
    let (_, test) = split(&records, 4096);
    let x = features(&test[0].reading);
    let mut group = c.benchmark_group("contact_mlp");
    for head in Head::ALL {
        let mlp = ContactMlp::load(&root.join(MODEL_DIR).join(model_file(4096, head)))
            .expect("committed model");
        group.bench_function(format!("{}/forward", head.name()), |b| {
            b.iter(|| mlp.outputs(black_box(&x)))
        });
        group.bench_function(format!("{}/locate", head.name()), |b| {
            b.iter(|| mlp.predict(black_box(&x)))
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
