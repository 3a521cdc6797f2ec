//! One grasp-loop cycle's compute, without I/O: contact estimate from three pad pressures,
//! the paper's fuzzy controller (seed 000 §5, 9 × 9 rules, center average), the torque band
//! and the gripper command. Target: < 20 µs per cycle.

use criterion::{Criterion, criterion_group, criterion_main};
use hand_control::grasp_loop::{PressureEstimator, TorqueBand};
use hand_traits::{GraspPolicy, GripperCommand, PressureFrame};
use std::hint::black_box;

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("grasp_cycle");
    let band = TorqueBand::new(80, 400).expect("Table 5 cube band");
    let mut policy = fuzzy_mamdani::grasp_controller().with_torque_band(80, 400);
    let mut est = PressureEstimator::<3>::new(50.0, 10.0);
    est.tare(&PressureFrame {
        t_us: 0,
        pressure_pa: [101_000.0; 3],
    })
    .expect("finite");
    est.finish_tare().expect("tared");
    // A pressure ramp through the controller's universe, so the fuzzy rules that fire vary.
    let mut t_us = 0_u64;
    group.bench_function("estimate+fuzzy+command", |b| {
        b.iter(|| {
            t_us += 10_000;
            let rise = (t_us / 10_000 % 400) as f32 * 10.0;
            let frame = PressureFrame {
                t_us,
                pressure_pa: [101_000.0 + rise, 101_010.0 + rise, 100_990.0 + rise],
            };
            let e = est.update(black_box(&frame)).expect("finite frame");
            let effort = policy.effort(&e.observation(1_500.0)).expect("finite");
            let (effort, _) = band.clamp(effort);
            black_box(GripperCommand {
                position_rad: 0.2,
                effort,
            })
        })
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
