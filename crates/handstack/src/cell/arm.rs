//! A Universal Robots arm as a node (`/arm0`): `joint_states` (`sensor_msgs/JointState`) and
//! `tcp_pose` (`geometry_msgs/PoseStamped`, the UR rotation vector as a quaternion) at the
//! node's rate, in the arm's base frame ([`frames::base_frame`]: `arm0_base`); `goal`
//! (`PoseStamped`) in: each goal in that frame starts a moveL to it, a newer goal replacing the
//! move under way (a goal in any other frame is refused and counted: the node does not
//! transform poses); the service `stop` (`std_srvs/Trigger`): stopL.
//!
//! Safe state: when the last node publishing goals leaves the graph while the arm moves (its
//! liveliness token goes: a crash, a kill, a lost link), the arm is stopped (stopL) at once;
//! so it is when the node itself stops, however it stops. The link to the controller is
//! checked every cycle: a controller that goes away ends the node, saying so.

use super::commanders::Commanders;
use super::error::CellError;
use super::frames;
use crate::pace::Pacer;
use crate::stop::Stop;
use hand_traits::LinearMotion;
use hand_zenoh::convert::{header, pose_from_msg, pose_to_msg};
use hand_zenoh::msg::geometry_msgs::PoseStamped;
use hand_zenoh::msg::sensor_msgs::JointState;
use hand_zenoh::msg::std_srvs::{Trigger, TriggerResponse};
use hand_zenoh::node::{Node, now_ns};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use ur_bridge::{MoveHandle, UrArm};

/// The joints' names, as Universal Robots' ROS 2 driver calls them.
pub const UR_JOINTS: [&str; 6] = [
    "shoulder_pan_joint",
    "shoulder_lift_joint",
    "elbow_joint",
    "wrist_1_joint",
    "wrist_2_joint",
    "wrist_3_joint",
];

/// How the arm node runs.
#[derive(Debug, Clone)]
pub struct ArmNodeConfig {
    /// State messages (and move polls) per second.
    pub rate_hz: f64,
    /// The frame id of its messages and of the goals it takes (`arm0_base`).
    pub frame_id: String,
    /// Speed and acceleration of the moves.
    pub motion: LinearMotion,
    /// stopL's deceleration, m/s².
    pub stop_decel_m_per_s2: f64,
}

impl Default for ArmNodeConfig {
    fn default() -> Self {
        ArmNodeConfig {
            rate_hz: 50.0,
            frame_id: frames::base_frame("/arm0"),
            motion: LinearMotion::default(),
            stop_decel_m_per_s2: 1.2,
        }
    }
}

/// What the arm node did.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct ArmNodeReport {
    /// Goals taken (each started a move).
    pub goals: u64,
    /// Goals refused: not in the arm's base frame.
    pub refused: u64,
    /// Goal samples whose attachment could not be read (neither rmw_zenoh layout).
    pub unreadable: u64,
    /// Moves that ran to their end.
    pub moves_done: u64,
    /// stopL on request (the `stop` service).
    pub stops: u64,
    /// stopL because the goals' publisher left the graph mid-move.
    pub safe_stops: u64,
}

impl core::fmt::Display for ArmNodeReport {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write!(
            f,
            "{} goals, {} refused (another frame), {} unreadable, {} moves done, {} stops \
             asked, {} safe stops",
            self.goals, self.refused, self.unreadable, self.moves_done, self.stops, self.safe_stops
        )
    }
}

/// Runs the arm node on `node` until `stop`.
pub fn run(
    node: &Node,
    arm: &mut UrArm,
    config: &ArmNodeConfig,
    stop: &Stop,
) -> Result<ArmNodeReport, CellError> {
    let host = arm.config().host.clone();
    let ur = |e: ur_bridge::UrError| CellError::Device {
        device: "arm",
        reason: format!("controller at {host}: {e}"),
    };
    let mut goals = node.subscription::<PoseStamped>("goal", 16)?;
    let mut joints = node.publisher::<JointState>("joint_states")?;
    let mut tcp = node.publisher::<PoseStamped>("tcp_pose")?;
    let asked = Arc::new(AtomicBool::new(false));
    let flag = Arc::clone(&asked);
    let _stop_service = node.service::<Trigger, _>("stop", move |_| {
        flag.store(true, Ordering::Relaxed);
        TriggerResponse {
            success: true,
            message: "stopL".to_owned(),
        }
    })?;
    let mut commanders = Commanders::watch(node, "goal")?;
    let mut current: Option<MoveHandle> = None;
    let mut report = ArmNodeReport::default();
    let mut pacer = Pacer::new(config.rate_hz);
    // One message, its names set once; each cycle updates its stamp and positions.
    let mut joint_msg = JointState {
        name: UR_JOINTS.iter().map(|n| (*n).to_owned()).collect(),
        position: vec![0.0; UR_JOINTS.len()],
        ..JointState::default()
    };
    // The loop, in a closure so that every way out of it (`?` included) reaches the stop below.
    let mut body = || -> Result<(), CellError> {
        loop {
            // A stop request first: it is answered before the node looks at anything else.
            if asked.swap(false, Ordering::Relaxed) {
                current = None;
                arm.stop_linear(config.stop_decel_m_per_s2).map_err(ur)?;
                report.stops += 1;
            }
            if stop.is_set() {
                return Ok(());
            }
            // The link is watched every cycle: a controller gone (powered off, its process
            // killed, the cable pulled) ends the node at once.
            if !arm.is_connected().map_err(ur)? {
                return Err(ur(ur_bridge::UrError::ConnectionLost));
            }
            if commanders.last_left()? && current.take().is_some() {
                arm.stop_linear(config.stop_decel_m_per_s2).map_err(ur)?;
                report.safe_stops += 1;
            }
            let mut latest = None;
            while let Some(g) = goals.try_recv()? {
                if g.message.header.frame_id == config.frame_id {
                    latest = Some(g.message);
                } else {
                    report.refused += 1;
                }
            }
            super::unreadable::say_new(&mut goals);
            report.unreadable = goals.stats().refused;
            if let Some(goal) = latest {
                report.goals += 1;
                current = Some(
                    arm.start_move_linear(&pose_from_msg(&goal.pose), &config.motion)
                        .map_err(ur)?,
                );
            }
            if let Some(h) = &current {
                if !arm.progress(h).map_err(ur)?.running {
                    current = None;
                    report.moves_done += 1;
                }
            }
            let h = header(now_ns(), &config.frame_id);
            let pose = arm.tool_pose().map_err(ur)?;
            let q = arm.joint_positions().map_err(ur)?;
            tcp.publish(&PoseStamped {
                header: h.clone(),
                pose: pose_to_msg(&pose),
            })?;
            joint_msg.header = h;
            joint_msg.position.copy_from_slice(&q);
            joints.publish(&joint_msg)?;
            pacer.wait();
        }
    };
    let ended = body();
    // However the node ended, an arm still moving is stopped (stopL), if it can be told.
    let left = match current {
        None => "arm not moving".to_owned(),
        Some(_) => match arm.stop_linear(config.stop_decel_m_per_s2) {
            Ok(()) => {
                report.safe_stops += 1;
                "arm stopped mid-move (stopL)".to_owned()
            }
            Err(e) => {
                format!("the arm's stop (stopL) could not be sent ({e}): it may finish its move")
            }
        },
    };
    match ended {
        Ok(()) => Ok(report),
        Err(e) => Err(CellError::Left {
            error: Box::new(e),
            left,
        }),
    }
}
