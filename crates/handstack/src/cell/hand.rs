//! A grasp hand as a node (`/hand0`): hand-control's grasp loop (fingertip → contact estimate
//! → the paper's Mamdani controller → Protocol 2.0 hand) with, each cycle, `tactile/raw` (the
//! loop's frame), `grasp/state` (`handstack_msgs/GraspState`) and `gripper/joint_states`;
//! `gripper/command` (`handstack_msgs/GripperCommand`) in: its position becomes the loop's goal
//! (the effort stays the controller's); services `grasp/start` (start cycling: tare, then
//! grasp) and `grasp/stop` (the hand's safe action, then idle). With a force DNN
//! ([`HandNodeConfig::force`]) also `force` (`geometry_msgs/WrenchStamped`) each cycle once the
//! loop has tared, from the loop's frame and zero.
//!
//! Safe state: when the last node publishing commands leaves the graph while the loop runs (its
//! command stream stops: a crash, a kill, a lost link), the hand goes to its configured safe
//! action at once and the loop idles until started again. When the node ends — stopped (a
//! signal, stdin closed), or at the first fault its scene does not recover from — the hand
//! gets its end action (`[hand] on_end`: release by default), as in `handstack run`.

use super::commanders::Commanders;
use super::error::CellError;
use crate::error::{Ending, RunError};
use crate::pace::Pacer;
use crate::record::grasp::grasp_state;
use crate::runs::grasp::{FaultWatch, left_text};
use crate::scene::experiment::Recover;
use crate::scene::force::ForceNet;
use crate::stop::Stop;
use hand_control::grasp_loop::{GraspLoop, LoopClock, LoopConfig, RebootableActuator};
use hand_traits::{PressureFrame, TactileSource};
use hand_zenoh::convert::header;
use hand_zenoh::force::{ForceTopic, rise_hpa};
use hand_zenoh::msg::handstack_msgs::{self as hs, GraspState, GripperCommand};
use hand_zenoh::msg::sensor_msgs::JointState;
use hand_zenoh::msg::std_srvs::{Trigger, TriggerResponse};
use hand_zenoh::node::{Node, now_ns};
use std::sync::Arc;
use std::sync::atomic::{AtomicU8, Ordering};

/// How the hand node runs.
#[derive(Debug, Clone)]
pub struct HandNodeConfig {
    /// Cycles per second the node paces the loop at (a loop on a real clock paces itself).
    pub rate_hz: f64,
    /// The frame id of its messages (`hand0`).
    pub frame_id: String,
    /// The force DNN `force` is published from (`None`: no `force` topic).
    pub force: Option<ForceNet>,
    /// What the hand is called in messages (`servo bus /dev/ttyUSB0`).
    pub hand: String,
    /// The scene's recovery (`None`: the first fault ends the node).
    pub recover: Option<Recover>,
}

/// What the hand node did.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct HandNodeReport {
    /// Loop cycles run.
    pub cycles: u64,
    /// Goals taken from `gripper/command`.
    pub commands: u64,
    /// Commands refused: a goal outside the loop's limits (never sent to the hand).
    pub refused: u64,
    /// Command samples whose attachment could not be read (neither rmw_zenoh layout).
    pub unreadable: u64,
    /// `grasp/start` calls that started the loop.
    pub starts: u64,
    /// `grasp/stop` calls that stopped it.
    pub stops: u64,
    /// Safe actions because the command stream's publisher left mid-grasp (or the node
    /// stopped while the loop ran).
    pub safe_stops: u64,
    /// Force estimates published on `force`.
    pub forces: u64,
    /// Frames the force DNN refused (counted, not published).
    pub forces_refused: u64,
    /// Published forces beyond the force DNN's rated range (its saturated output).
    pub forces_beyond_range: u64,
    /// What the end action left the hand doing, in words.
    pub left: String,
}

impl core::fmt::Display for HandNodeReport {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write!(
            f,
            "{} cycles; goals: {} taken, {} refused, {} unreadable; {} starts, {} stops, {} safe stops; \
             forces: {} published ({} beyond the model's range), {} frames refused; hand {}",
            self.cycles,
            self.commands,
            self.refused,
            self.unreadable,
            self.starts,
            self.stops,
            self.safe_stops,
            self.forces,
            self.forces_beyond_range,
            self.forces_refused,
            self.left
        )
    }
}

const IDLE: u8 = 0;
const START: u8 = 1;
const STOP: u8 = 2;

/// Runs the hand node on `node` until `stop`: the paper's controller in `config.band` drives
/// `hand` from `tip` on `clock`.
pub fn run<S, A, C>(
    node: &Node,
    tip: S,
    hand: A,
    clock: C,
    config: LoopConfig,
    node_config: &HandNodeConfig,
    stop: &Stop,
) -> Result<HandNodeReport, CellError>
where
    S: TactileSource<Frame = PressureFrame<3>>,
    S::Error: core::fmt::Display,
    A: RebootableActuator,
    A::Error: std::error::Error + 'static,
    C: LoopClock,
{
    let config = LoopConfig {
        recovery: crate::runs::grasp::recovery(node_config.recover),
        ..config
    };
    let band = config.band;
    let safe_action = config.safe_action;
    let policy = fuzzy_mamdani::grasp_controller().with_torque_band(band.min_raw(), band.max_raw());
    let mut grasp = GraspLoop::new(tip, policy, hand, clock, config)
        .map_err(|e| CellError::device("grasp loop", e))?;
    let mut raw = node.publisher::<hs::PressureFrame>("tactile/raw")?;
    let mut state = node.publisher::<GraspState>("grasp/state")?;
    let mut joints = node.publisher::<JointState>("gripper/joint_states")?;
    let mut force = match node_config.force.clone() {
        Some(model) => Some(ForceTopic::new(node, model)?),
        None => None,
    };
    let mut commands = node.subscription::<GripperCommand>("gripper/command", 16)?;
    let asked = Arc::new(AtomicU8::new(IDLE));
    let service = |what: u8, text: &'static str| {
        let flag = Arc::clone(&asked);
        move |_| {
            flag.store(what, Ordering::Relaxed);
            TriggerResponse {
                success: true,
                message: text.to_owned(),
            }
        }
    };
    let _start = node.service::<Trigger, _>("grasp/start", service(START, "grasping"))?;
    let _stop = node.service::<Trigger, _>("grasp/stop", service(STOP, "safe action sent"))?;
    let mut commanders = Commanders::watch(node, "gripper/command")?;
    let mut running = false;
    let mut report = HandNodeReport::default();
    let mut faults = FaultWatch::new(node_config.recover, &node_config.hand);
    let mut pacer = Pacer::new(node_config.rate_hz);
    // One message, its name set once; each cycle updates its stamp and values.
    let mut joint_msg = JointState {
        name: vec!["gripper".to_owned()],
        position: vec![0.0],
        velocity: vec![0.0],
        // JointState's effort is N·m (or N): the servo reports a load fraction, which
        // `grasp/state` carries; so no effort here rather than a number in another unit.
        effort: Vec::new(),
        ..JointState::default()
    };
    let safe = |grasp: &mut GraspLoop<_, _, A, C, 3>| {
        grasp
            .actuator_mut()
            .safe_stop(safe_action)
            .map_err(|e| CellError::device("hand", e))
    };
    // The loop, in a closure so that every way out of it (`?` included) reaches the end
    // action below. `Ok(Some(what))`: a fault ended it.
    let mut body = || -> Result<Option<String>, CellError> {
        loop {
            match asked.swap(IDLE, Ordering::Relaxed) {
                START if !running => {
                    running = true;
                    report.starts += 1;
                }
                STOP if running => {
                    running = false;
                    report.stops += 1;
                    safe(&mut grasp)?;
                }
                _ => {}
            }
            if stop.is_set() {
                return Ok(None);
            }
            if commanders.last_left()? && running {
                running = false;
                report.safe_stops += 1;
                safe(&mut grasp)?;
            }
            while let Some(c) = commands.try_recv()? {
                match grasp.set_goal_rad(c.message.position_rad) {
                    Ok(()) => report.commands += 1,
                    Err(_) => report.refused += 1,
                }
            }
            super::unreadable::say_new(&mut commands);
            report.unreadable = commands.stats().refused;
            if running {
                let sample = *grasp.cycle();
                report.cycles += 1;
                if let Some(what) = faults.check(&grasp, &sample) {
                    return Ok(Some(what));
                }
                let h = header(now_ns(), &node_config.frame_id);
                if let Some(f) = sample.frame {
                    raw.publish(&hs::PressureFrame {
                        header: h.clone(),
                        pressure_pa: f.pressure_pa.to_vec(),
                    })?;
                    if let (Some(topic), Some(zero)) = (&mut force, grasp.zero_pa()) {
                        let zero = zero.map(|z| z as f32);
                        if topic.publish(h.clone(), &rise_hpa(&f.pressure_pa, &zero))? {
                            report.forces += 1;
                        }
                    }
                }
                let gs = sample.state;
                state.publish(&grasp_state(&sample, h.clone()))?;
                if let Some(s) = gs {
                    joint_msg.header = h;
                    joint_msg.position[0] = f64::from(s.position_rad);
                    joint_msg.velocity[0] = f64::from(s.velocity_rad_per_s);
                    joints.publish(&joint_msg)?;
                }
            }
            pacer.wait();
        }
    };
    let ended = body();
    if running {
        report.safe_stops += 1;
    }
    // The one shutdown path: however the loop ended, the hand gets its end action now.
    let end = grasp.end();
    let last_torque = grasp.log().iter().rev().find_map(|s| s.torque_raw);
    report.left = left_text(&end, last_torque);
    // The topic counts what its estimator refused and what lay beyond its range.
    report.forces_refused = force.as_ref().map_or(0, ForceTopic::refused);
    report.forces_beyond_range = force.as_ref().map_or(0, ForceTopic::beyond_range);
    match ended {
        Ok(None) => Ok(report),
        Ok(Some(what)) => Err(CellError::from(RunError::Ended {
            ending: Ending::Fault,
            what: format!("{what}; hand {}", report.left),
        })),
        Err(e) => Err(CellError::Left {
            error: Box::new(e),
            left: format!("hand {}", report.left),
        }),
    }
}
