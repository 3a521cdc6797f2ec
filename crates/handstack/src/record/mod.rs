//! Recording a run (`handstack run SCENE --record DIR`): every frame, estimate, command, fault
//! and figure, as they happen, in a rosbag2 bag with MCAP storage (`record::bag`) that
//! Foxglove opens and `ros2 bag play` replays, in the messages and topics the `handstack node`
//! parts publish (hand-zenoh's `msg`):
//!
//! | topic | type | when |
//! |---|---|---|
//! | `/hand0/tactile/raw` | `handstack_msgs/msg/PressureFrame` | each fingertip frame (grasp cycle, readout) |
//! | `/hand0/tactile/mcu` | `handstack_msgs/msg/FingertipFrame` | each frame of a fingertip's microcontroller (contact) |
//! | `/hand0/grasp/state` | `handstack_msgs/msg/GraspState` | each grasp cycle |
//! | `/hand0/gripper/joint_states` | `sensor_msgs/msg/JointState` | each grasp cycle the servos answered |
//! | `/hand0/gripper/command` | `handstack_msgs/msg/GripperCommand` | each command the loop sent |
//! | `/hand0/fingers/raw` | `handstack_msgs/msg/FingerFrame` | each reading of the underactuated hand |
//! | `/hand0/softness` | `handstack_msgs/msg/Softness` | the softness classification |
//! | `/pad0/imu` | `sensor_msgs/msg/Imu` | each ICM-20789 pad frame (tap-to-move) |
//! | `/handstack/fault` | `handstack_msgs/msg/Fault` | each fault a cycle saw; what ended a run |
//! | `/handstack/figures` | `handstack_msgs/msg/Figure` | each figure, at the end of its experiment |
//! | `/handstack/labels` | `handstack_msgs/msg/Label` | each step of a guided collect session (`handstack collect`) |
//!
//! Stamps (header and bag time) are the wall clock when the run had the value, ns since the
//! Unix epoch, as the nodes stamp theirs; a cycle's messages share its stamp.

mod bag;
pub mod grasp;
pub mod mcu;
pub mod pad;
pub mod read;

pub use bag::{FLUSH_EVERY, METADATA_VERSION, ROS_DISTRO, TopicId};

use crate::Figure;
use bag::Bag;
use hand_zenoh::convert::header;
use hand_zenoh::msg::Message;
use hand_zenoh::msg::builtin_interfaces::Time;
use hand_zenoh::msg::handstack_msgs::{self as hs, Fault, FingerFrame};
use hand_zenoh::msg::sensor_msgs::ChannelFloat32;
use hand_zenoh::msg::tactile_msgs::TactileState;
use std::path::{Path, PathBuf};
use std::sync::{Mutex, PoisonError};
use std::time::{SystemTime, UNIX_EPOCH};

/// The namespace of the hand's topics, as `handstack node` names a hand part.
pub const HAND_NS: &str = "/hand0";
/// The frame id of the hand's messages.
pub const HAND_FRAME: &str = "hand0";
/// The topic of every figure.
pub const FIGURES: &str = "/handstack/figures";
/// The topic of faults and of what ended a run.
pub const FAULTS: &str = "/handstack/fault";
/// The topic of a collect session's labels: what the user was asked to do, over which frames.
pub const LABELS: &str = "/handstack/labels";

/// Why a recording could not be made or went on no longer.
#[derive(Debug, thiserror::Error)]
pub enum RecordError {
    /// `--record` names a directory that already holds files.
    #[error(
        "cannot record into {}: the directory is not empty (a bag is a directory of its own: \
         name a new one)",
        dir.display()
    )]
    NotEmpty {
        /// The directory.
        dir: PathBuf,
    },
    /// `--record` names a file.
    #[error("cannot record into {}: it is a file, not a directory", path.display())]
    NotADirectory {
        /// The path.
        path: PathBuf,
    },
    /// The directory or the bag file could not be created.
    #[error("cannot create the recording at {}: {reason}", path.display())]
    Create {
        /// What could not be created.
        path: PathBuf,
        /// The system's answer.
        reason: String,
    },
    /// Writing to the bag failed (a full disk, a directory gone): recording stopped there; the
    /// bag up to its last flush is kept.
    #[error("recording to {} stopped: {reason}; the bag up to then is kept", path.display())]
    Write {
        /// The bag's directory.
        path: PathBuf,
        /// The system's answer.
        reason: String,
    },
}

/// One label of a collect session (see [`Recorder::label`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Labelled<'a> {
    /// The experiment that asked (`weight`).
    pub experiment: &'a str,
    /// What is labelled (`tare`, `weight_gf`).
    pub name: &'a str,
    /// Its value.
    pub value: f64,
    /// The first frame it covers, ns since the Unix epoch (the frames' bag time).
    pub start_ns: u64,
    /// The last frame it covers.
    pub end_ns: u64,
}

/// Nanoseconds since the Unix epoch, now.
pub fn now_ns() -> u64 {
    SystemTime::now()
        .duration_since(UNIX_EPOCH)
        .map_or(0, |d| u64::try_from(d.as_nanos()).unwrap_or(u64::MAX))
}

/// A bag being recorded, shared by the runners of one `handstack run` (one bag for all its
/// scenes). A write that fails stops the recording (the run goes on, its devices are not
/// touched); [`Recorder::finish`] then returns that error.
pub struct Recorder {
    dir: PathBuf,
    state: Mutex<State>,
}

impl core::fmt::Debug for Recorder {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("Recorder").field("dir", &self.dir).finish()
    }
}

struct State {
    bag: Option<Bag>,
    failed: Option<RecordError>,
}

impl Recorder {
    /// Creates the bag directory `dir` (new, or empty) and starts its bag.
    pub fn create(dir: &Path) -> Result<Recorder, RecordError> {
        let mut bag = Bag::create(dir)?;
        bag.custom(
            "recorded_by",
            &format!("handstack {}", env!("CARGO_PKG_VERSION")),
        );
        Ok(Recorder {
            dir: dir.to_owned(),
            state: Mutex::new(State {
                bag: Some(bag),
                failed: None,
            }),
        })
    }

    /// The bag's directory.
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// Runs `f` on the bag unless recording stopped; a failure stops it.
    fn with<T>(&self, f: impl FnOnce(&mut Bag) -> Result<T, RecordError>) -> Option<T> {
        let mut s = self.state.lock().unwrap_or_else(PoisonError::into_inner);
        let bag = s.bag.as_mut()?;
        match f(bag) {
            Ok(v) => Some(v),
            Err(e) => {
                s.bag = None;
                s.failed = Some(e);
                None
            }
        }
    }

    /// The topic `name` of type `M` (declared in the bag on first use; `None` once recording
    /// stopped).
    pub fn topic<M: Message>(&self, name: &str) -> Option<TopicId> {
        self.with(|b| b.topic::<M>(name))
    }

    /// Writes `msg` on `topic` at `t_ns`.
    pub fn write<M: Message>(&self, topic: Option<TopicId>, t_ns: u64, msg: &M) {
        if let Some(topic) = topic {
            self.with(|b| b.write(topic, t_ns, msg));
        }
    }

    /// Records `figures` of scene `scene`, stamped now.
    pub fn figures(&self, scene: &str, figures: &[Figure]) {
        let topic = self.topic::<hs::Figure>(FIGURES);
        let t = now_ns();
        for f in figures {
            let msg = hs::Figure {
                header: header(t as i64, scene),
                name: f.name.clone(),
                label: f.label.clone(),
                value: f.value,
                unit: f.unit.clone(),
                paper: f.paper.unwrap_or(f64::NAN),
                source: f.source.clone().unwrap_or_default(),
                target: f.target.clone().unwrap_or_default(),
                met: f.met.map_or(-1, i8::from),
            };
            self.write(topic, t, &msg);
        }
    }

    /// Records a fault from `source` (a part as the scene names it, or `run`).
    pub fn fault(&self, frame_id: &str, source: &str, what: &str, ends_run: bool) {
        let topic = self.topic::<Fault>(FAULTS);
        let t = now_ns();
        let msg = Fault {
            header: header(t as i64, frame_id),
            source: source.to_owned(),
            what: what.to_owned(),
            ends_run,
        };
        self.write(topic, t, &msg);
    }

    /// Records that the frames of `device` stamped `start_ns..=end_ns` are `name` = `value`
    /// of `experiment` (a collect session's truth: `weight`, `weight_gf`, 50).
    pub fn label(&self, device: &str, label: &Labelled<'_>) {
        let topic = self.topic::<hs::Label>(LABELS);
        let t = now_ns();
        let msg = hs::Label {
            header: header(t as i64, device),
            experiment: label.experiment.to_owned(),
            name: label.name.to_owned(),
            value: label.value,
            start: Time::from_nanos(label.start_ns),
            end: Time::from_nanos(label.end_ns),
        };
        self.write(topic, t, &msg);
    }

    /// Adds `key: value` to the bag's `custom_data` (the scenes recorded).
    pub fn note(&self, key: &str, value: &str) {
        self.with(|b| {
            b.custom(key, value);
            Ok(())
        });
    }

    /// Ends the bag: summary, footer, final `metadata.yaml`. Returns the messages recorded, or
    /// why recording stopped early (the bag up to then is kept).
    pub fn finish(&self) -> Result<u64, RecordError> {
        let mut s = self.state.lock().unwrap_or_else(PoisonError::into_inner);
        if let Some(e) = s.failed.take() {
            return Err(e);
        }
        match s.bag.take() {
            Some(mut bag) => bag.finish(),
            None => Ok(0),
        }
    }
}

/// A tactile sensor's values as the ROS tactile toolbox reads them: `tactile_msgs/TactileState`
/// on `/hand0/tactile_states` (the toolbox's topic, in the hand's namespace), one named array,
/// beside our own message of the same reading.
pub struct TactileStateTopic<'r> {
    recorder: &'r Recorder,
    topic: Option<TopicId>,
    msg: TactileState,
}

impl<'r> TactileStateTopic<'r> {
    /// Declares the topic on `recorder` for sensor `name` of `n` values.
    pub fn new(recorder: &'r Recorder, name: &str, n: usize) -> Self {
        TactileStateTopic {
            recorder,
            topic: recorder.topic::<TactileState>(&format!("{HAND_NS}/tactile_states")),
            msg: TactileState {
                header: header(0, HAND_FRAME),
                sensors: vec![ChannelFloat32 {
                    name: name.to_owned(),
                    values: vec![0.0; n],
                }],
            },
        }
    }

    /// Records `values` (as many as declared) at `t_ns`.
    pub fn record(&mut self, t_ns: u64, values: &[f32]) {
        self.msg.header.stamp = hand_zenoh::msg::builtin_interfaces::Time::from_nanos(t_ns);
        if let Some(s) = self.msg.sensors.first_mut() {
            for (v, x) in s.values.iter_mut().zip(values) {
                *v = *x;
            }
        }
        self.recorder.write(self.topic, t_ns, &self.msg);
    }
}

/// The topic of the fingertip's frames, `/hand0/tactile/raw`.
pub fn raw_topic() -> String {
    format!("{HAND_NS}/tactile/raw")
}

/// The topic of the underactuated hand's readings, `/hand0/fingers/raw`.
pub fn fingers_topic() -> String {
    format!("{HAND_NS}/fingers/raw")
}

/// The underactuated hand's readings as `/hand0/fingers/raw`, one reused message, and its four
/// FSR forces (N) as the tactile sensor `fsr` on `/hand0/tactile_states`.
pub struct FingerTopic<'r> {
    recorder: &'r Recorder,
    topic: Option<TopicId>,
    msg: FingerFrame,
    tactile: TactileStateTopic<'r>,
}

impl<'r> FingerTopic<'r> {
    /// Declares the topic on `recorder`.
    pub fn new(recorder: &'r Recorder) -> Self {
        FingerTopic {
            recorder,
            topic: recorder.topic::<FingerFrame>(&fingers_topic()),
            msg: FingerFrame {
                header: header(0, HAND_FRAME),
                force_n: vec![0.0; 4],
                distal_angle_rad: vec![0.0; 4],
            },
            tactile: TactileStateTopic::new(recorder, "fsr", 4),
        }
    }

    /// Records one reading: forces (N) then distal angles (degrees), the softness net's order;
    /// its bag time, ns since the Unix epoch.
    pub fn record(&mut self, sample: &[f32; 8]) -> u64 {
        let t = now_ns();
        self.msg.header.stamp = hand_zenoh::msg::builtin_interfaces::Time::from_nanos(t);
        self.msg.force_n.copy_from_slice(&sample[..4]);
        for (a, deg) in self.msg.distal_angle_rad.iter_mut().zip(&sample[4..]) {
            *a = deg.to_radians();
        }
        self.recorder.write(self.topic, t, &self.msg);
        self.tactile.record(t, &sample[..4]);
        t
    }
}
