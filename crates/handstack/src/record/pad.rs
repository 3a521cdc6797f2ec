//! The ICM-20789 pad's frames as the pad node publishes them: `/pad0/imu`.

use super::{Recorder, TopicId};
use hand_traits::ImuFrame;
use hand_zenoh::convert::{header, imu_to_msg, set_imu};
use hand_zenoh::msg::builtin_interfaces::Time;
use hand_zenoh::msg::sensor_msgs::Imu;

/// The namespace of the pad's topics, as `handstack node` names a pad part.
pub const PAD_NS: &str = "/pad0";
/// The frame id of the pad's messages.
pub const PAD_FRAME: &str = "pad0";

/// The pad's frames on `/pad0/imu` (`sensor_msgs/Imu`, accelerometer and gyroscope), one
/// reused message.
pub struct ImuTopic<'r> {
    recorder: &'r Recorder,
    topic: Option<TopicId>,
    msg: Imu,
}

/// The topic of the pad's frames.
pub fn imu_topic() -> String {
    format!("{PAD_NS}/imu")
}

impl<'r> ImuTopic<'r> {
    /// Declares the topic on `recorder`.
    pub fn new(recorder: &'r Recorder) -> Self {
        let rest = ImuFrame {
            t_us: 0,
            accel_mps2: [0.0; 3],
            gyro_rps: [0.0; 3],
            pressure_pa: None,
        };
        ImuTopic {
            recorder,
            topic: recorder.topic::<Imu>(&imu_topic()),
            msg: imu_to_msg(&rest, header(0, PAD_FRAME)),
        }
    }

    /// Records frame `f` at `t_ns`.
    pub fn record(&mut self, t_ns: u64, f: &ImuFrame) {
        set_imu(&mut self.msg, f);
        self.msg.header.stamp = Time::from_nanos(t_ns);
        self.recorder.write(self.topic, t_ns, &self.msg);
    }
}
