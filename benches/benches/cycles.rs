//! One full control cycle per scene, and each of its stages alone, with in-process simulated
//! devices (see the crate docs). A stage benched alone replays the inputs it received inside
//! the full cycle over a recorded stretch of the same schedule — including the cycles in
//! which it had nothing to do — so the stages' means add up to the cycle's.
//!
//! Ids: `cycle_<scene>/full` for the whole cycle, `cycle_<scene>/<stage>` for a stage.
//! `cargo xtask bench cycles [-- --quick]`; `cargo xtask bench cycles --write` also writes
//! `docs/benchmarks.md`.

use criterion::{Criterion, criterion_group, criterion_main};
use handstack_benches::contact::ContactCycle;
use handstack_benches::full_hand::FullHandCycle;
use handstack_benches::grasp::{GraspCycle, TARE_FRAMES};
use handstack_benches::replay::Replay;
use handstack_benches::softness::SoftnessCycle;
use handstack_benches::tap::TapCycle;
use handstack_benches::weight::WeightCycle;
use std::hint::black_box;

/// Cycles recorded for the stage replays (after the warm-up the tares need).
const RECORD: usize = 2_000;

fn replay<T>(items: Vec<T>) -> Replay<T> {
    Replay::new(items).expect("recorded cycles")
}

fn weight(c: &mut Criterion) {
    let mut g = c.benchmark_group("cycle_weight");
    let mut full = WeightCycle::new().expect("weight cycle");
    g.bench_function("full", |b| {
        b.iter(|| black_box(full.cycle().expect("cycle")))
    });
    let mut rec = WeightCycle::new().expect("weight cycle");
    let outs: Vec<_> = (0..RECORD).map(|_| rec.cycle().expect("cycle")).collect();
    let mut dev = WeightCycle::new().expect("weight cycle");
    g.bench_function("decode", |b| {
        b.iter(|| black_box(dev.decode().expect("frame")))
    });
    let mut frames = replay(outs.iter().map(|o| o.frame).collect());
    let mut est = WeightCycle::new().expect("weight cycle");
    g.bench_function("estimate", |b| {
        b.iter(|| black_box(est.estimate(frames.next_item())))
    });
    let mut rises = replay(outs.iter().map(|o| o.rise_hpa).collect());
    g.bench_function("policy", |b| {
        b.iter(|| black_box(rec.policy(rises.next_item()).expect("finite")))
    });
    g.finish();
}

fn contact(c: &mut Criterion) {
    let mut g = c.benchmark_group("cycle_contact");
    let mut full = ContactCycle::new().expect("contact cycle");
    g.bench_function("full", |b| {
        b.iter(|| black_box(full.cycle().expect("cycle")))
    });
    let mut rec = ContactCycle::new().expect("contact cycle");
    let outs: Vec<_> = (0..RECORD).map(|_| rec.cycle().expect("cycle")).collect();
    let mut dev = ContactCycle::new().expect("contact cycle");
    g.bench_function("decode", |b| {
        b.iter(|| black_box(dev.decode().expect("frame")))
    });
    let mut frames = replay(outs.iter().map(|o| o.estimate.frame).collect());
    let mut est = ContactCycle::new().expect("contact cycle");
    g.bench_function("estimate", |b| {
        b.iter(|| black_box(est.estimate(frames.next_item())))
    });
    let mut events = replay(outs.iter().map(|o| o.estimate.event).collect());
    g.bench_function("aot", |b| {
        b.iter(|| {
            let e = *events.next_item();
            black_box(e.map(|e| rec.aot(&e).expect("arrived")))
        })
    });
    let mut readings = replay(outs.iter().map(|o| o.estimate.reading).collect());
    g.bench_function("mlp", |b| {
        b.iter(|| {
            let r = *readings.next_item();
            black_box(r.map(|r| rec.mlp(&r).expect("finite")))
        })
    });
    g.finish();
}

fn grasp(c: &mut Criterion) {
    let mut g = c.benchmark_group("cycle_grasp");
    let mut full = GraspCycle::new().expect("grasp cycle");
    g.bench_function("full", |b| {
        b.iter(|| black_box(full.cycle().expect("cycle").packets.len()))
    });
    let mut rec = GraspCycle::new().expect("grasp cycle");
    let mut outs = Vec::with_capacity(RECORD);
    for _ in 0..RECORD {
        let o = rec.cycle().expect("cycle");
        outs.push((o.frame, o.estimate, o.command));
    }
    let mut dev = GraspCycle::new().expect("grasp cycle");
    g.bench_function("decode", |b| {
        b.iter(|| black_box(dev.decode().expect("frame")))
    });
    // The estimator wants increasing stamps: replayed frames are re-stamped at the frame rate.
    let period_us = outs[1].0.t_us - outs[0].0.t_us;
    let mut frames = replay(
        outs.iter()
            .skip(TARE_FRAMES as usize)
            .map(|o| o.0)
            .collect(),
    );
    let mut est = GraspCycle::new().expect("grasp cycle");
    let mut t_us = 0;
    for o in outs.iter().take(TARE_FRAMES as usize) {
        est.estimate(&o.0).expect("tare");
        t_us = o.0.t_us;
    }
    g.bench_function("estimate", |b| {
        b.iter(|| {
            let mut f = *frames.next_item();
            t_us += period_us;
            f.t_us = t_us;
            black_box(est.estimate(&f).expect("finite"))
        })
    });
    let mut estimates = replay(outs.iter().map(|o| o.1).collect());
    g.bench_function("policy", |b| {
        b.iter(|| {
            let e = *estimates.next_item();
            black_box(e.map(|e| rec.policy(&e).expect("finite")))
        })
    });
    let mut commands = replay(outs.iter().map(|o| o.2).collect());
    g.bench_function("encode", |b| {
        b.iter(|| {
            let cmd = *commands.next_item();
            black_box(cmd.map(|c| rec.encode(&c).expect("in range").1.len()))
        })
    });
    g.finish();
}

fn softness(c: &mut Criterion) {
    let mut g = c.benchmark_group("cycle_softness");
    let mut full = SoftnessCycle::new().expect("softness cycle");
    g.bench_function("full", |b| {
        b.iter(|| black_box(full.cycle().expect("cycle")))
    });
    let mut rec = SoftnessCycle::new().expect("softness cycle");
    let n = rec.reads_per_round();
    let decoded: Vec<_> = (0..n).map(|_| rec.decode()).collect();
    g.bench_function("decode", |b| b.iter(|| black_box(rec.decode())));
    let mut frames = replay(decoded.iter().map(|d| d.1).collect());
    g.bench_function("estimate", |b| {
        b.iter(|| black_box(SoftnessCycle::estimate(frames.next_item())))
    });
    let mut samples = replay(
        decoded
            .iter()
            .map(|(r, f)| (r.grasp, SoftnessCycle::estimate(f)))
            .collect(),
    );
    g.bench_function("policy", |b| {
        b.iter(|| {
            let (grasp, s) = *samples.next_item();
            black_box(rec.policy(grasp, &s).expect("finite"))
        })
    });
    g.finish();
}

fn tap(c: &mut Criterion) {
    let mut g = c.benchmark_group("cycle_tap");
    let mut full = TapCycle::new().expect("tap cycle");
    g.bench_function("full", |b| {
        b.iter(|| black_box(full.cycle().expect("cycle")))
    });
    let mut rec = TapCycle::new().expect("tap cycle");
    let outs: Vec<_> = (0..RECORD).map(|_| rec.cycle().expect("cycle")).collect();
    let mut dev = TapCycle::new().expect("tap cycle");
    g.bench_function("decode", |b| {
        b.iter(|| black_box(dev.decode().expect("frame")))
    });
    // The window cutter wants frames in time order: replayed frames are re-stamped.
    let period_us = outs[1].frame.t_us - outs[0].frame.t_us;
    let mut frames = replay(outs.iter().map(|o| o.frame).collect());
    let mut est = TapCycle::new().expect("tap cycle");
    let mut t_us = 0;
    g.bench_function("estimate", |b| {
        b.iter(|| {
            let mut f = *frames.next_item();
            t_us += period_us;
            f.t_us = t_us;
            black_box(est.estimate(f).expect("window"))
        })
    });
    let mut rec2 = TapCycle::new().expect("tap cycle");
    let windows: Vec<_> = outs
        .iter()
        .map(|o| rec2.estimate(o.frame).expect("window"))
        .collect();
    let mut windows = replay(windows);
    g.bench_function("policy", |b| {
        b.iter(|| {
            let w = windows.next_item();
            black_box(w.as_ref().map(|w| rec.policy(w).expect("finite")))
        })
    });
    let mut regions = replay(
        outs.iter()
            .map(|o| o.prediction.map(|p| p.region))
            .collect(),
    );
    g.bench_function("encode", |b| {
        b.iter(|| {
            let r = *regions.next_item();
            black_box(r.map(|r| rec.encode(r).expect("grid region")))
        })
    });
    g.finish();
}

fn full_hand(c: &mut Criterion) {
    let mut g = c.benchmark_group("cycle_full_hand");
    let mut full = FullHandCycle::new().expect("full-hand cycle");
    g.bench_function("full", |b| {
        b.iter(|| black_box(full.cycle().expect("cycle")))
    });
    g.finish();
}

criterion_group!(benches, weight, contact, grasp, softness, tap, full_hand);
criterion_main!(benches);
