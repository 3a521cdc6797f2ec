//! Sync-write + sync-read round trip over the pty against the simulator (2–4 MX-28s at a
//! nominal 1 Mbps), next to the time the same bytes take on a real 1 Mbps wire; and the cost of
//! encoding one gripper command.
//!
//! Run with `cargo xtask bench servo_bus`. The wire time is printed per servo count.

use std::hint::black_box;
use std::time::Duration;

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use dxl_sim::{REPLY_LATENCY, SimBus, SimConfig};
use hand_control::ServoHand;
use hand_control::protocol::{encode, instruction_id, packet_id};
use hand_traits::{Effort, GripperActuator, GripperCommand};

const BAUD: u64 = 1_000_000;

/// Bytes of one cycle on the wire: two sync writes (Goal PWM 2 B, Goal Position 4 B), one sync
/// read of the 10-byte state block, and one status packet per servo.
fn cycle_bytes(n: usize) -> usize {
    let ids: Vec<u8> = (1..=n as u8).collect();
    let mut wire = Vec::new();
    for width in [2usize, 4] {
        let mut p = vec![0, 0, width as u8, 0];
        for &id in &ids {
            p.push(id);
            p.extend(std::iter::repeat_n(0, width));
        }
        encode(
            &mut wire,
            packet_id::BROADCAST,
            instruction_id::SYNC_WRITE,
            &p,
        );
    }
    let mut p = vec![126, 0, 10, 0];
    p.extend_from_slice(&ids);
    encode(
        &mut wire,
        packet_id::BROADCAST,
        instruction_id::SYNC_READ,
        &p,
    );
    for &id in &ids {
        encode(&mut wire, id, 0x55, &[0; 11]);
    }
    wire.len()
}

fn round_trip(c: &mut Criterion) {
    let mut g = c.benchmark_group("servo_bus/round_trip");
    for n in [2usize, 3, 4] {
        let ids: Vec<u8> = (1..=n as u8).collect();
        let (sim, port) = SimBus::spawn(SimConfig::with_ids(&ids)).expect("pty");
        let mut hand = ServoHand::with_reply_latency(port, &ids, REPLY_LATENCY).expect("hand");
        for &id in &ids {
            // Return Delay Time 0: compare against the bytes alone.
            hand.write_register(id, 9, 0).expect("return delay");
        }
        hand.set_torque(true).expect("torque");
        let bytes = cycle_bytes(n);
        let wire = Duration::from_nanos(bytes as u64 * 10 * 1_000_000_000 / BAUD);
        eprintln!("servo_bus: {n} servos: {bytes} bytes per cycle = {wire:?} on a 1 Mbps wire");
        let cmd = GripperCommand {
            position_rad: 3.0,
            effort: Effort::from_torque_limit_raw(400),
        };
        g.bench_with_input(BenchmarkId::from_parameter(n), &n, |b, _| {
            b.iter(|| {
                hand.command(black_box(&cmd)).expect("command");
                black_box(hand.read_states().expect("state"))
            })
        });
        drop(hand);
        drop(sim);
    }
    g.finish();
}

fn encoding(c: &mut Criterion) {
    let (_sim, port) = SimBus::spawn(SimConfig::with_ids(&[1, 2])).expect("pty");
    let hand = ServoHand::with_reply_latency(port, &[1, 2], REPLY_LATENCY).expect("hand");
    let cmd = GripperCommand {
        position_rad: 3.0,
        effort: Effort::from_torque_limit_raw(400),
    };
    let mut wire = Vec::with_capacity(64);
    c.bench_function("servo_bus/encode_command", |b| {
        b.iter(|| {
            let goals = hand.encode_command(black_box(&cmd)).expect("in range");
            wire.clear();
            let t = hand.table();
            for (reg, v) in [
                (t.goal_effort, goals.effort),
                (t.goal_position, goals.position),
            ] {
                let bytes = reg.encode(v);
                let w = usize::from(reg.width);
                let mut p = [0u8; 4 + 2 * 5];
                p[..2].copy_from_slice(&reg.address.to_le_bytes());
                p[2..4].copy_from_slice(&u16::from(reg.width).to_le_bytes());
                for (k, &id) in hand.ids().iter().enumerate() {
                    let at = 4 + k * (1 + w);
                    p[at] = id;
                    p[at + 1..at + 1 + w].copy_from_slice(&bytes[..w]);
                }
                encode(
                    &mut wire,
                    packet_id::BROADCAST,
                    instruction_id::SYNC_WRITE,
                    &p[..4 + 2 * (1 + w)],
                );
            }
            black_box(wire.len())
        })
    });
}

criterion_group!(benches, round_trip, encoding);
criterion_main!(benches);
