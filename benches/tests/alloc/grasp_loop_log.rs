//! What `hand_control::grasp_loop::GraspLoop::cycle` itself allocates, over the same parts as
//! the grasp scene's cycle: hand-sim's fingertip (frame log off), the paper's fuzzy controller,
//! an in-process gripper that encodes the goal sync writes, a simulated clock. The loop keeps
//! every cycle's `Sample` in its log `Vec`: memory grows by one sample a cycle and the `Vec`
//! reallocates each time it doubles — the one allocation left in the grasp loop.

use hand_control::control_table::MX_28;
use hand_control::grasp_loop::{GraspLoop, LoopClock, LoopConfig, RebootableActuator, Sample};
use hand_control::{GoalPackets, encode_goals};
use hand_sim::fingertip::{Fingertip, FingertipConfig};
use hand_traits::{Faults, GripperActuator, GripperCommand, GripperState, SafeAction};

/// A gripper in memory: encodes each command as `ServoHand::write_goals` does (without the
/// port write), reports no fault.
struct InProcessGripper(GoalPackets, usize);

impl GripperActuator for InProcessGripper {
    type Error = handstack_benches::CycleError;
    fn command(&mut self, cmd: &GripperCommand) -> Result<(), Self::Error> {
        let goals = encode_goals(&MX_28, cmd)
            .map_err(|e| handstack_benches::CycleError::Config(e.to_string()))?;
        self.1 += self.0.encode(&goals).len();
        Ok(())
    }
    fn state(&mut self) -> Result<GripperState, Self::Error> {
        Ok(GripperState {
            position_rad: 0.0,
            velocity_rad_per_s: 0.0,
            load_fraction: 0.0,
            faults: Faults::NONE,
        })
    }
    fn safe_stop(&mut self, _: SafeAction) -> Result<(), Self::Error> {
        Ok(())
    }
}

impl RebootableActuator for InProcessGripper {
    fn reboot(&mut self) -> Result<(), Self::Error> {
        Ok(())
    }
    fn enable_torque(&mut self) -> Result<(), Self::Error> {
        Ok(())
    }
}

/// Simulated loop time: waiting jumps the clock.
struct SimTime(u64);

impl LoopClock for SimTime {
    fn now_us(&mut self) -> u64 {
        self.0
    }
    fn wait_until_us(&mut self, t: u64) {
        self.0 = self.0.max(t);
    }
}

fn the_grasp_loop_allocates_only_to_grow_its_log() {
    const WARM_UP: u64 = 200;
    const CYCLES: u64 = 2_000;
    let config = FingertipConfig {
        osr: 1024,
        ..FingertipConfig::default()
    };
    let mut tip = Fingertip::new(&config, 13).expect("fingertip");
    tip.set_frame_log(false);
    let gripper = InProcessGripper(GoalPackets::new(&MX_28, &[1, 2]), 0);
    let policy = fuzzy_mamdani::grasp_controller().with_torque_band(80, 400);
    let mut grasp =
        GraspLoop::new(tip, policy, gripper, SimTime(0), LoopConfig::new()).expect("valid config");
    let _profiler = dhat::Profiler::builder().testing().build();
    for _ in 0..WARM_UP {
        grasp.cycle();
    }
    let before = dhat::HeapStats::get();
    for _ in 0..CYCLES {
        grasp.cycle();
    }
    let after = dhat::HeapStats::get();
    let blocks = after.total_blocks - before.total_blocks;
    let grown = after.curr_bytes - before.curr_bytes;
    let sample = std::mem::size_of::<Sample<3>>();
    println!(
        "GraspLoop::cycle: {blocks} blocks in {CYCLES} cycles after {WARM_UP}; heap +{grown} B \
         ({sample} B per logged sample); {} wire bytes sent",
        grasp.actuator_mut().1
    );
    assert!(grasp.events().is_empty(), "{:?}", grasp.events());
    assert!(grasp.actuator_mut().1 > 0, "the loop grasped");
    // The log keeps every sample: the heap grows by at least one per cycle…
    assert!(grown >= CYCLES as usize * sample, "{grown} B");
    // …through a doubling Vec: from 200 to 2 200 samples, a handful of reallocations.
    let doublings = (f64::from((WARM_UP + CYCLES) as u32) / WARM_UP as f64)
        .log2()
        .ceil() as u64;
    assert!(
        blocks <= doublings + 1,
        "{blocks} blocks, {doublings} doublings"
    );
}

/// The check, printing its name once it passed.
pub(crate) fn run() {
    the_grasp_loop_allocates_only_to_grow_its_log();
    println!("the_grasp_loop_allocates_only_to_grow_its_log: ok");
}
