//! A grasp loop's cycle and a fingertip's frames as the hand node's messages: the one place a
//! [`Sample`] becomes `GraspState` (the hand node publishes the same), and the reused messages
//! a recording writes each cycle without allocating.

use super::{HAND_FRAME, HAND_NS, Recorder, TactileStateTopic, TopicId, now_ns};
use hand_control::grasp_loop::{Mode, Sample};
use hand_traits::Effort;
use hand_zenoh::convert::header;
use hand_zenoh::msg::builtin_interfaces::Time;
use hand_zenoh::msg::handstack_msgs::{GraspState, GripperCommand, PressureFrame};
use hand_zenoh::msg::sensor_msgs::JointState;
use hand_zenoh::msg::std_msgs::Header;

/// `GraspState.mode`: 0 tare, 1 grasp, 2 safe, 3 halted.
pub fn mode_code(m: Mode) -> u8 {
    match m {
        Mode::Tare => 0,
        Mode::Grasp => 1,
        Mode::Safe => 2,
        Mode::Halted => 3,
    }
}

/// Cycle `s` as `GraspState` under `header`.
pub fn grasp_state(s: &Sample<3>, header: Header) -> GraspState {
    let gs = s.state;
    GraspState {
        header,
        mode: mode_code(s.mode),
        pressure_pa: s.estimate.map_or(f32::NAN, |e| e.pressure_pa),
        in_contact: s.estimate.is_some_and(|e| e.in_contact),
        effort: s
            .torque_raw
            .map_or(0.0, |r| Effort::from_torque_limit_raw(r).fraction()),
        position_rad: gs.map_or(f32::NAN, |s| s.position_rad),
        load_fraction: gs.map_or(f32::NAN, |s| s.load_fraction),
        faults: gs.map_or(0, |s| s.faults.bits()),
    }
}

/// A fingertip's frames as `/hand0/tactile/raw`, one reused message, and as the tactile sensor
/// `fingertip` (three pressures, Pa) on `/hand0/tactile_states`.
pub struct RawTopic<'r> {
    recorder: &'r Recorder,
    topic: Option<TopicId>,
    msg: PressureFrame,
    tactile: TactileStateTopic<'r>,
}

impl<'r> RawTopic<'r> {
    /// Declares the topic on `recorder`.
    pub fn new(recorder: &'r Recorder) -> Self {
        RawTopic {
            recorder,
            topic: recorder.topic::<PressureFrame>(&super::raw_topic()),
            msg: PressureFrame {
                header: header(0, HAND_FRAME),
                pressure_pa: vec![0.0; 3],
            },
            tactile: TactileStateTopic::new(recorder, "fingertip", 3),
        }
    }

    /// Records one frame at `t_ns`.
    pub fn record(&mut self, t_ns: u64, pressure_pa: &[f32; 3]) {
        self.msg.header.stamp = Time::from_nanos(t_ns);
        self.msg.pressure_pa.copy_from_slice(pressure_pa);
        self.recorder.write(self.topic, t_ns, &self.msg);
        self.tactile.record(t_ns, pressure_pa);
    }
}

/// A grasp loop's topics: `tactile/raw`, `grasp/state`, `gripper/joint_states` and
/// `gripper/command`, each a reused message.
pub struct GraspTopics<'r> {
    recorder: &'r Recorder,
    raw: RawTopic<'r>,
    state: Option<TopicId>,
    joints: Option<TopicId>,
    command: Option<TopicId>,
    state_msg: GraspState,
    joint_msg: JointState,
    command_msg: GripperCommand,
}

impl<'r> GraspTopics<'r> {
    /// Declares the topics on `recorder`.
    pub fn new(recorder: &'r Recorder) -> Self {
        GraspTopics {
            recorder,
            raw: RawTopic::new(recorder),
            state: recorder.topic::<GraspState>(&format!("{HAND_NS}/grasp/state")),
            joints: recorder.topic::<JointState>(&format!("{HAND_NS}/gripper/joint_states")),
            command: recorder.topic::<GripperCommand>(&format!("{HAND_NS}/gripper/command")),
            state_msg: GraspState {
                header: header(0, HAND_FRAME),
                ..GraspState::default()
            },
            // As the hand node publishes it: one joint, no effort (the servo's load fraction
            // is in `grasp/state`, not N·m).
            joint_msg: JointState {
                header: header(0, HAND_FRAME),
                name: vec!["gripper".to_owned()],
                position: vec![0.0],
                velocity: vec![0.0],
                effort: Vec::new(),
            },
            command_msg: GripperCommand {
                header: header(0, HAND_FRAME),
                ..GripperCommand::default()
            },
        }
    }

    /// Records cycle `s`, stamped now.
    pub fn record(&mut self, s: &Sample<3>) {
        let t = now_ns();
        let stamp = Time::from_nanos(t);
        if let Some(f) = s.frame {
            self.raw.record(t, &f.pressure_pa);
        }
        let h = core::mem::take(&mut self.state_msg.header.frame_id);
        self.state_msg = grasp_state(
            s,
            Header {
                stamp: stamp.clone(),
                frame_id: h,
            },
        );
        self.recorder.write(self.state, t, &self.state_msg);
        if let Some(st) = s.state {
            self.joint_msg.header.stamp = stamp.clone();
            self.joint_msg.position[0] = f64::from(st.position_rad);
            self.joint_msg.velocity[0] = f64::from(st.velocity_rad_per_s);
            self.recorder.write(self.joints, t, &self.joint_msg);
        }
        if let (Some(raw), Some(goal)) = (s.torque_raw, s.goal_rad) {
            self.command_msg.header.stamp = stamp;
            self.command_msg.position_rad = goal;
            self.command_msg.effort = Effort::from_torque_limit_raw(raw).fraction();
            self.recorder.write(self.command, t, &self.command_msg);
        }
    }
}
