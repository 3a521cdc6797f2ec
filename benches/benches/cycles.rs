//! Wall time of every workload of `handstack_benches::workloads`: one full control cycle per
//! scene, each of its stages alone, and the compute kernels (see the crate docs). A stage
//! benched alone replays the inputs it received inside the full cycle over a recorded
//! stretch of the same schedule — including the cycles in which it had nothing to do — so the
//! stages' means add up to the cycle's. `tests/instructions.rs` counts the same calls'
//! instructions.
//!
//! Ids: `cycle_<scene>/full`, `cycle_<scene>/<stage>`, `kernel/<name>`.
//! `cargo xtask bench cycles [-- --quick]`; `cargo xtask bench cycles --write` also writes
//! `docs/benchmarks.md`.

use criterion::{Criterion, criterion_group, criterion_main};
use handstack_benches::workloads::{GROUPS, group};

fn all(c: &mut Criterion) {
    for name in GROUPS {
        let workloads = group(name).expect("workloads build");
        let mut g = c.benchmark_group(name);
        for mut w in workloads {
            let function = w.id.rsplit('/').next().unwrap_or(w.id);
            g.bench_function(function, |b| b.iter(|| (w.call)()));
        }
        g.finish();
    }
}

criterion_group!(benches, all);
criterion_main!(benches);
