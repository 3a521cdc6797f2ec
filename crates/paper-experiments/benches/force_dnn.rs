//! Force / weight DNN: single-sample f32 inference (frozen form, and dfdx's forward for
//! comparison) on the committed Table 1 model, and training wall time of the committed
//! recipes (Table 1: 10 000 full-batch epochs; simulated series: one recipe epoch of 4 600
//! frames, the whole recipe being 200 such epochs).

use criterion::{Criterion, criterion_group, criterion_main};
use paper_experiments::data::weights;
use paper_experiments::force_eval::{self, MODEL_DIR, RATED_RANGE_GF, SEED, TABLE_FILE};
use std::hint::black_box;
use std::path::Path;
use tactile_nets::force_dnn::ForceDnn;

fn bench(c: &mut Criterion) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let rows: Vec<(f64, [f64; 3])> = paper_fixtures::seed000::table1_weight()
        .expect("Table 1")
        .iter()
        .map(|r| (r.weight_gf, r.pressure_hpa))
        .collect();
    let table = weights::tared_table(&rows).expect("tared Table 1");
    let dnn = ForceDnn::load(&root.join(MODEL_DIR).join(TABLE_FILE)).expect("committed model");
    let x = table[5].rise_hpa;
    let mut group = c.benchmark_group("force_dnn");
    group.bench_function("infer/frozen", |b| {
        b.iter(|| dnn.estimate_gf(black_box(&x)))
    });
    group.bench_function("infer/dfdx", |b| {
        b.iter(|| dnn.estimate_gf_dfdx(black_box(&x)))
    });
    group.sample_size(10);
    group.bench_function("train/table1", |b| {
        b.iter(|| {
            ForceDnn::train(
                &table,
                RATED_RANGE_GF,
                &force_eval::table_recipe(SEED, false, ""),
            )
        })
    });
    let frames = weights::load_series(&root).expect("committed series");
    let (train, _) = force_eval::sim_split(&frames).expect("sim split");
    let mut one_epoch = force_eval::sim_recipe(SEED, false);
    one_epoch.truncate(1);
    one_epoch[0].epochs = 1;
    group.bench_function("train/sim_epoch", |b| {
        b.iter(|| ForceDnn::train(&train, RATED_RANGE_GF, &one_epoch))
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
