//! The fused full-hand loop's faults: a fingertip bus error, a pad bus error, a silent servo and
//! the arm's lost connection each end the loop in its safe state in the cycle they are seen, and the figures name the device
//! and the time. The loop runs on the full-hand scene's simulated stack; its UR simulators sit
//! on 127.0.0.210 and up.

use crate::common;

use common::scene_path;
use hand_control::grasp_loop::Mode;
use hand_traits::{ImuFrame, TactileSource};
use handstack::progress::Quiet;
use paper_experiments::grasp_rig::{Injected, Injection};
use paper_scenes::runs::RunContext;
use paper_scenes::runs::hand_loop::scene::{self, Built};
use paper_scenes::scene::PaperScene as Scene;
use std::time::{Duration, Instant};

fn built() -> Built {
    paper_scenes::devices::arm::sim_addresses_from(210);
    let cx = RunContext::new(&Quiet);
    let s = Scene::load(&scene_path("full-hand")).expect("the committed scene loads");
    scene::build(&s, &cx)
        .expect("the simulated stack opens")
        .expect("the full hand names a grasp and taps")
}

/// The pad, failing from its `fail_at`-th read on (0-based) as a bus that stopped answering.
struct FailingPad {
    pad: hand_sim::imu_pad::ImuPad,
    reads: u64,
    fail_at: u64,
}

impl TactileSource for FailingPad {
    type Frame = ImuFrame;
    type Error = String;
    fn read_frame(&mut self) -> Result<ImuFrame, String> {
        self.reads += 1;
        if self.reads > self.fail_at {
            return Err("injected: the pad's bus stopped answering".into());
        }
        self.pad.read_frame().map_err(|e| e.to_string())
    }
}

#[test]
fn a_pad_bus_error_ends_the_loop_in_the_hold_within_its_cycle() {
    paper_scenes::devices::arm::sim_addresses_from(210);
    let cx = RunContext::new(&Quiet);
    let s = Scene::load(&scene_path("full-hand")).expect("the committed scene loads");
    // 150 frames at 30 Hz: the 151st read is due 5 s after the first tick.
    let mut b = scene::build_with(&s, &cx, |pad| FailingPad {
        pad,
        reads: 0,
        fail_at: 150,
    })
    .expect("the simulated stack opens")
    .expect("the full hand names a grasp and taps");
    b.hand_loop.run_until(b.until_us);
    let t_us = ended_in_safe_state(&b, "sensors.imu_pad");
    assert!((4_990_000..=5_010_000).contains(&t_us), "{t_us}");
    // The failed read is not counted: 150 frames were read.
    assert_eq!(b.hand_loop.stats().pad_reads, 150);
}

/// The loop ended in `device`'s fault: the fault's cycle was the last one run, and the hand
/// is in its safe state.
fn ended_in_safe_state<Pad>(b: &Built<Pad>, device: &str) -> u64
where
    Pad: TactileSource<Frame = ImuFrame>,
    Pad::Error: core::fmt::Display,
{
    let l = &b.hand_loop;
    let f = l.fault().expect("a fault ended the loop");
    assert_eq!(f.device, device, "{f:?}");
    assert_eq!(f.mode, Mode::Safe, "{f:?}");
    assert_eq!(l.stats().cycles, f.cycle + 1, "no cycle after the fault's");
    assert_eq!(l.grasp().log().last().map(|s| s.cycle), Some(f.cycle));
    let part = b.figures();
    let fig = |n: &str| part.figures.iter().find(|x| x.name == n).expect(n).clone();
    assert_eq!(fig("loop_fault").value, 1.0);
    assert!(
        fig("loop_fault").label.contains(device),
        "{:?}",
        fig("loop_fault")
    );
    assert_eq!(fig("loop_fault_t_s").value, f.t_us as f64 * 1e-6);
    f.t_us
}

#[test]
fn a_fingertip_bus_error_ends_the_loop_in_the_hold_within_its_cycle() {
    let mut b = built();
    b.environment
        .as_ref()
        .expect("a simulated grasp")
        .inject(Injection {
            from_s: 5.0,
            until_s: 5.5,
            kind: Injected::TactileBus,
        });
    b.hand_loop.run_until(b.until_us);
    let t_us = ended_in_safe_state(&b, "sensors.fingertip");
    // The first cycle whose read falls in the window (its tick, or the next one).
    assert!((5_000_000..=5_010_000).contains(&t_us), "{t_us}");
    let last = b
        .hand_loop
        .grasp()
        .log()
        .last()
        .copied()
        .expect("cycles ran");
    assert!(last.safe_action.is_some(), "{last:?}");
    assert!(
        b.hand_loop
            .fault()
            .is_some_and(|f| f.reason.contains("injected"))
    );
    // Simulated time: the loop kept its period up to the fault.
    assert_eq!(b.hand_loop.overruns(), 0);
}

#[test]
fn losing_the_arm_mid_move_ends_the_loop_in_the_hold_within_its_cycle() {
    let mut b = built();
    b.hand_loop.run_until(1_000_000);
    let far = *handstack::tap_to_move::RegionToGrid::ur3_default()
        .expect("the UR3 grid")
        .pose(8)
        .expect("region 8");
    b.hand_loop.arm_mut().request(far);
    b.hand_loop.run_until(1_100_000);
    assert!(b.hand_loop.arm_mut().busy());
    let before = b.hand_loop.stats().cycles;
    b.sim.take().expect("the scene's arm is simulated").kill();
    // The loop runs on at its period until the arm's client sees the loss (wall time: the
    // controller's sockets closing), bounded.
    let wall = Instant::now();
    while b.hand_loop.cycle() && wall.elapsed() < Duration::from_secs(20) {}
    let t_us = ended_in_safe_state(&b, "arm");
    assert!(b.hand_loop.stats().cycles > before);
    assert!(t_us >= 1_100_000, "{t_us}");
}

#[test]
fn a_dropped_servo_status_ends_the_loop_in_the_hold_within_its_cycle() {
    let mut b = built();
    b.environment
        .as_ref()
        .expect("a simulated grasp")
        .inject(Injection {
            from_s: 6.0,
            until_s: 6.5,
            kind: Injected::Silent,
        });
    b.hand_loop.run_until(b.until_us);
    let t_us = ended_in_safe_state(&b, "hand");
    assert!((6_000_000..=6_020_000).contains(&t_us), "{t_us}");
}
